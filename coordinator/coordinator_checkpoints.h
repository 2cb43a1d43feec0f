#pragma once
// The coordinator's side of checkpoints and restart (docs/checkpoints.md): the interval (fixed
// steps: a whole multiple of every domain's step; variable steps: as asked, written at the
// leader's first instant at or after each multiple), the instant a restart resumes from, and the
// coordinator's own checkpoint (the interface histories up to it, the vectors it routed, its CPU),
// written once a daemon has announced the instant and every interface's history rows reached it.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/coupling_history.h"
#include "coordinator/layer_cut.h"
#include "coupling/layer_router.h"
#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"
#include "solver/run/checkpoint_store.h"

namespace crashlink::coordinator {

class CoordinatorCheckpoints {
 public:
  /// The folder name of the coordinator's checkpoints beside the daemons' (run/checkpoint_store.h).
  static constexpr const char* kSelf = run::kCoordinatorPiece;

  /// `options` and `cut` must outlive this object; `hash` is the scenario's.
  CoordinatorCheckpoints(const CoordinatorOptions& options, const LayerCut& cut, std::string hash);

  /// The interval in ticks from options.checkpoint_interval_s (0: none), logged. Fixed steps:
  /// rounded to a whole multiple (>= 1) of the least common multiple of `steps`, so every domain
  /// is between two cycles there. Variable steps: as asked; the cut must have one leader (a domain
  /// that holds no ghosts). Throws InputError otherwise, with the leaders' names or the values.
  coupling::Tick plan(const std::vector<coupling::Tick>& steps);
  coupling::Tick every() const { return every_; }

  /// The newest instant at which the coordinator (if `any_interface`: without one it keeps no state
  /// of its own) and every daemon (regs[k].checkpoint_ticks, cut order: the daemons list only
  /// their intact ones) have an intact checkpoint; logs the coordinator's damaged ones, and the
  /// fall-back when a newer instant is missing or damaged in some piece. Throws InputError
  /// listing what each has when there is none.
  coupling::Tick choose_restart(const std::vector<wire::Register>& regs, bool any_interface) const;
  /// Router and interface histories as they were at T (nothing to restore without an interface).
  /// Returns the CPU time [s] of the run(s) before T. Throws CheckpointError for a checkpoint of
  /// another scenario or cut.
  double restore(coupling::Tick T, coupling::LayerRouter& router, CouplingHistory& history);
  coupling::Tick restarted_from() const { return restart_from_; }  ///< -1: from t = 0

  /// After a LayerReport: interface i's history rows have reached `time`.
  void rows_reached(std::uint32_t i, coupling::Tick time);
  /// A daemon announced its checkpoint at `time` (LayerReport.checkpoint). Every daemon does:
  /// an instant already written is not written again.
  void announced(coupling::Tick time);
  std::int64_t written() const { return written_; }  ///< checkpoints written by this run
  /// Writes the coordinator's checkpoint at every announced instant that every interface's rows
  /// have reached, with `cpu_seconds` the run's CPU time so far.
  void write_when_complete(const coupling::LayerRouter& router, CouplingHistory& history,
                           double cpu_seconds);
  /// At the end of a run that every daemon finished (their checkpoints all committed): removes
  /// every piece's checkpoints older than the newest 3 complete instants, which a piece that
  /// committed before the others could not yet remove (run/checkpoint_store.h).
  void prune_all() const;

 private:
  void plan_variable();
  void log(const std::string& line) const;
  void write(coupling::Tick time, const coupling::LayerRouter& router, CouplingHistory& history,
             double cpu_seconds);

  const CoordinatorOptions& o_;
  const LayerCut& cut_;
  std::string hash_;
  std::vector<std::string> pieces_;  ///< every domain, and the coordinator with an interface
  coupling::Tick every_ = 0;
  coupling::Tick restart_from_ = -1;
  std::set<coupling::Tick> due_;        ///< instants announced, not written yet
  coupling::Tick latest_written_ = -1;  ///< the newest instant written (or restored)
  std::int64_t written_ = 0;
  std::vector<coupling::Tick> row_latest_;  ///< [interfaces] instant of the latest history row
};

}  // namespace crashlink::coordinator
