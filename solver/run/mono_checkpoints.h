#pragma once
// Checkpoints and restart of the mono run (docs/checkpoints.md "mono"): one piece, the mono
// domain, in OUT/checkpoints/<T>/<domain>/ (checkpoint_store.h), written at the first cycle
// boundary at or after each multiple of the interval (domain_checkpoint.h says what it holds).
// A mono run's time is a double: T is its time in ticks of kMonoTicksPerSecond, rounded, and only
// names the folder; the solver's own time comes back from the checkpoint to the bit.
#include <cstdint>
#include <limits>
#include <string>

#include "solver/integration/solver.h"
#include "solver/run/domain_checkpoint.h"
#include "solver/run/domain_recorder.h"

namespace crashlink::run {

/// 1 fs, the coupled runs' default tick (coupling/ticks.h kDefaultTicksPerSecond).
inline constexpr std::int64_t kMonoTicksPerSecond = 1'000'000'000'000'000;

struct MonoCheckpointOptions {
  std::string out_dir;
  std::string domain;         ///< the mono run's domain name: its piece
  std::string scenario_hash;  ///< io::scenario_hash of the scenario file
  double interval_s = 0.0;    ///< simulated time between checkpoints (0: none)
};

class MonoCheckpoints {
 public:
  /// Throws InputError for an interval that does not fit a tick count.
  explicit MonoCheckpoints(MonoCheckpointOptions options);

  bool enabled() const { return every_ > 0; }
  /// A run from t = 0: removes the piece's old checkpoints (never mixed with this run's) and
  /// announces the interval on stderr.
  void start_fresh() const;
  /// --restart, before the result file is opened: the newest intact checkpoint's instant, checked
  /// (read_domain_checkpoint). Prints each damaged one, and the fall-back when a newer one is
  /// damaged. Throws CheckpointError (exit 2) when OUT holds none, only damaged ones, a coupled
  /// run's, or one of another scenario.
  std::int64_t choose_restart() const;
  /// After solver.initialize(), into a new result file: the run as it was at T
  /// (domain_checkpoint.h). Returns the CPU time [s] of the run(s) before T.
  double restore(std::int64_t T, DomainRecorder& recorder, integration::Solver& solver);
  /// After Solver::end_cycle(): writes a checkpoint if the solver's time reached the next multiple
  /// of the interval and the run is not over. `cpu_seconds`: the run's CPU time so far.
  void after_cycle(DomainRecorder& recorder, const integration::Solver& solver, double cpu_seconds);

 private:
  DomainCheckpointSite site() const;

  MonoCheckpointOptions o_;
  std::int64_t every_ = 0;  ///< ticks (0: none)
  std::int64_t next_ = std::numeric_limits<std::int64_t>::max();
};

/// For a coupled --restart: throws CheckpointError (exit 2) when OUT holds only the checkpoints of
/// a mono run whose domain is `mono_domain`.
void refuse_mono_checkpoints(const std::string& out, const std::string& mono_domain);

}  // namespace crashlink::run
