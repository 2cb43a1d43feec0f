#pragma once
// One domain's /timing record, from its solver's cost counters.
#include <cstdint>
#include <string>

#include "solver/integration/solver.h"
#include "solver/io/result_writer.h"

namespace crashlink::run {

/// The record of `solver` as domain `name`: `cpu_s` the process's CPU over the run [s],
/// `elements` the domain's elements, `setup_cpu_s` its CPU before the first cycle [s]; cycles,
/// the smallest step, threads, the contacts' and kernels' costs and the peak memory come from
/// the solver and the process.
io::DomainTiming domain_timing(const integration::Solver& solver, std::string name, double cpu_s,
                               std::int64_t elements, double setup_cpu_s);

}  // namespace crashlink::run
