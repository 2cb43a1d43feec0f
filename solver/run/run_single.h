#pragma once
// Runs one model as one domain (the `mono` reference) to completion, writing DIR/result.h5.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/integration/energy.h"
#include "solver/integration/rigid_body.h"
#include "solver/model/model.h"
#include "solver/run/energy_summary.h"

namespace crashlink::run {

struct RunOptions {
  std::string out_dir = "out";
  bool progress = true;  ///< progress line on stderr
  std::string domain_name = "model";
  /// Threads computing the element forces (integration::Solver::set_threads; >= 1).
  int threads = 1;
  /// Polled every cycle (SIGINT / SIGTERM handler's flag); set: the run stops there, flushes
  /// and closes its file, and comes back with stopped = true.
  const std::atomic<bool>* stop = nullptr;
  /// Checkpoints (mono_checkpoints.h): one every this much simulated time [s] (0: none).
  double checkpoint_interval_s = 0.0;
  /// Resume the run in out_dir from its newest intact checkpoint (CheckpointError without one).
  bool restart = false;
  /// io::scenario_hash of the scenario file: recorded in the checkpoints, checked on a restart.
  std::string scenario_hash;
};

struct RunSummary {
  std::string domain;
  std::int64_t cycles = 0;
  std::int64_t elements = 0;
  int threads = 1;  ///< of the solver (cpu_seconds is theirs summed)
  double end_time_s = 0.0;
  double dt_min_s = 0.0;
  double cpu_seconds = 0.0;  ///< with a restart, that of the runs before the checkpoint too
  double wall_seconds = 0.0;
  integration::EnergyAccount energy;
  /// Each interface's contact energy at the end (model.contacts order; ContactStep::energy_J).
  std::vector<ContactEnergy> contacts;
  std::string result_h5;
  std::string result_xdmf;
  bool failed = false;   ///< the guard stopped the run
  std::string failure;   ///< its message
  bool stopped = false;  ///< RunOptions::stop was set: stopped on request at time end_time_s
  /// Spot welds that let go (integration::Solver::weld_failures), in order.
  std::vector<integration::WeldFailure> weld_failures;

  /// CPU nanoseconds per element per cycle (0 without elements or cycles).
  double ns_per_element_cycle() const;
};

/// Runs the model; output sampled at controls.history_interval_s / field_interval_s. On a
/// NumericalError the history so far, the last (finite) state and the timing are written, the
/// file is closed, and the summary comes back with failed = true (nothing is thrown).
/// Other errors (input, I/O, a refused checkpoint) propagate.
RunSummary run_single_domain(const model::Model& model, const RunOptions& options);

/// Prints the end-of-run table (cycles, CPU, step, energies, the contact energy of every
/// interface and what each created, energy balance, files) to `out` (energy_summary.h).
void print_summary(std::FILE* out, const RunSummary& s);

}  // namespace crashlink::run
