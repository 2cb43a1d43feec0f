#pragma once
// The headform of a result file, as compare, report and sweep read it: which probe is the head,
// its metrics after CFC 1000 (solver/signal/head_metrics.h), and the filtered curve as CSV.
#include <string>

#include "solver/io/result_reader.h"
#include "solver/signal/head_metrics.h"

namespace crashlink::apps {

/// The first probe on a rigid body (a headform), "" if the file has none.
std::string first_rigid_body_probe(const io::ResultReader& reader);

/// `probe`'s acceleration after CFC 1000: peak, HIC15, HIC36 and the filtered resultant.
signal::HeadMetrics result_head_metrics(const io::ResultReader& reader, const std::string& h5,
                                        const std::string& probe);

/// time_ms,accel_g of the filtered resultant (what tools/report.py plots); throws InputError
/// naming `who` when the file cannot be written.
void write_head_csv(const std::string& path, const signal::HeadMetrics& m, const char* who);

}  // namespace crashlink::apps
