#pragma once
// A daemon's checkpoints (docs/design.md §2.6 "Checkpoints", docs/checkpoints.md): the instants it
// can restart from (listed in its Register), the coordinator's interval (Setup), the pause before
// each multiple of it, and the files, written and read through run/domain_checkpoint.h with the
// scheme's own state beside the solver's.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/integration/solver.h"
#include "solver/partition/decomposition.h"
#include "solver/run/domain_checkpoint.h"
#include "solver/run/domain_recorder.h"

namespace crashlink::daemon {

class DaemonCheckpoints {
 public:
  using Tick = std::int64_t;
  static constexpr Tick kNever = std::numeric_limits<Tick>::max();

  /// The pieces are every domain of `dec` and the coordinator when it keeps state (a cut with an
  /// interface). Lists this domain's sound checkpoints; damaged ones are said on stderr.
  DaemonCheckpoints(std::string out_dir, std::string domain, std::string hash,
                    const partition::Decomposition& dec);
  const std::vector<Tick>& instants() const { return instants_; }  ///< for the Register

  /// A fresh start: another run's checkpoints are removed (not to be mixed with ours).
  void remove_old() const;
  /// The Setup's interval (0: none), from instant `now` on.
  void plan(Tick every, Tick now);
  /// Where the scheme must pause next (kNever: nowhere before the end).
  Tick until(Tick end) const { return next_ < end ? next_ : kNever; }
  bool enabled() const { return every_ > 0; }

  /// At `T` (seconds `t_s`) between two cycles: the result rows so far and the solver's state,
  /// with `save` adding the scheme's; the next pause is planned.
  void write(Tick T, double t_s, run::DomainRecorder& recorder, const integration::Solver& solver,
             double cpu_s, const std::function<void(core::StateWriter&)>& save);
  /// Resumes at T; returns the CPU time of the runs before it, s.
  double restore(Tick T, double t_s, run::DomainRecorder& recorder, integration::Solver& solver,
                 const std::function<void(const core::StateReader&)>& load);

 private:
  run::DomainCheckpointSite site() const;

  std::string out_dir_, domain_, hash_;
  std::vector<std::string> pieces_;
  std::vector<Tick> instants_;
  Tick every_ = 0;
  Tick next_ = kNever;
};

}  // namespace crashlink::daemon
