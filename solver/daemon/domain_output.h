#pragma once
// A daemon's result file, DIR/domains/<domain>.h5 and .xdmf (io::ResultWriter layout, the domain's
// sub-model), sampled at the instants a mono run samples (run/domain_recorder.h), with the
// domain's timing and spot weld failures at the end: what solver/gather reads back.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "solver/integration/solver.h"
#include "solver/io/result_writer.h"
#include "solver/run/domain_recorder.h"

namespace crashlink::daemon {

class DomainOutput {
 public:
  /// Creates the file (truncating another run's). A daemon may be killed by a failure elsewhere:
  /// at most a second of history stays unwritten.
  DomainOutput(const std::string& out_dir, const std::string& domain,
               const integration::Solver& solver);

  /// The solver was replaced (`paper`'s summed masses): sample that one.
  void follow(const integration::Solver& solver);
  /// The coupling scheme's energy share for the history (run::DomainRecorder::set_scheme_energy).
  void set_scheme_energy(std::function<std::pair<double, double>(double)> share_J);
  /// When a due field state may be written (run::DomainRecorder::set_field_gate).
  void set_field_gate(std::function<bool()> settled);
  void sample() { recorder_->sample(); }
  run::DomainRecorder& recorder() { return *recorder_; }
  const std::string& h5_path() const { return h5_path_; }
  /// The daemon's CPU before its first cycle, s (/timing setup_cpu_seconds).
  void set_setup_cpu(double cpu_s) { setup_cpu_s_ = cpu_s; }

  /// Timing (wall_s of the daemon, cpu_s of this domain) and welds, then closes the file.
  void finish(double wall_s, double cpu_s, std::int64_t elements);
  /// After a failure: what was sampled is flushed and the file closed, best effort.
  void close_after_failure(double wall_s, double cpu_s, std::int64_t elements) noexcept;

 private:
  void write_timing(double wall_s, double cpu_s, std::int64_t elements);

  std::string domain_;
  const integration::Solver* solver_;
  io::ResultWriter writer_;
  std::unique_ptr<run::DomainRecorder> recorder_;
  std::function<std::pair<double, double>(double)> scheme_energy_;
  std::function<bool()> field_gate_;
  std::string h5_path_;
  double setup_cpu_s_ = 0.0;
};

/// CRASHLINK_INJECT_INTERNAL_ERROR=DOMAIN:CYCLE makes that domain throw an unexpected exception at
/// that cycle: the one way to see, end to end, what a bug does to a run (exit 4 there, 5 for the
/// others, 4 from the launcher; docs/processes.md "Exit codes"). The cycle for `domain`, or -1.
/// Throws InputError for a value that is not DOMAIN:CYCLE.
std::int64_t injected_fault_cycle(const std::string& domain);

}  // namespace crashlink::daemon
