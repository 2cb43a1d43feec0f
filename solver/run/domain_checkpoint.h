#pragma once
// One domain's checkpoint (docs/checkpoints.md): what the mono run (mono_checkpoints.h) and a
// solver daemon (solver/daemon/daemon.cpp) both write at a cycle boundary and restore from, in
// OUT/checkpoints/<T>/<domain>/ (checkpoint_store.h):
//   state.bin: scenario hash, domain, kind of run, instant, the recorder's next sampling instants,
//              the CPU time so far, the solver's state (Solver::save_state), then what the caller
//              adds (a daemon: its stepper and its wait time);
//   a copy of the result file, flushed, holding every row and field state before T.
// A restart rebuilds the result file from that copy (io::replay_results) and goes on.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/integration/solver.h"
#include "solver/io/result_replay.h"
#include "solver/run/domain_recorder.h"

namespace crashlink::run {

/// Whose checkpoints, where, and how they are announced on stderr.
struct DomainCheckpointSite {
  std::string out_dir;
  std::string domain;
  std::string scenario_hash;  ///< io::scenario_hash of the scenario file
  /// "mono" or "coupled": a restart refuses the other kind's checkpoint of a same-named domain.
  std::string kind;
  std::vector<std::string> pieces;  ///< every piece of the run (commit_checkpoint prunes by them)
  std::string log_prefix;           ///< "crashlink-solver: domain 'body'", "crashlink: mono"
};

/// The kinds of DomainCheckpointSite::kind.
inline constexpr const char* kMonoKind = "mono";
inline constexpr const char* kCoupledKind = "coupled";

/// Writes the domain's checkpoint at instant `ticks` (`time_s` in seconds, for the log line) and
/// commits it (MANIFEST, then the older ones pruned); prints "<prefix>: checkpoint at t = ... s
/// (cycle ...), ... MB of state, ... ms". `extra` adds the caller's own records. Throws
/// CheckpointError / IoError.
void write_domain_checkpoint(const DomainCheckpointSite& site, std::int64_t ticks, double time_s,
                             DomainRecorder& recorder, const integration::Solver& solver,
                             double cpu_seconds,
                             const std::function<void(core::StateWriter&)>& extra = {});

struct DomainRestored {
  double cpu_seconds = 0.0;  ///< the CPU time of the run(s) before the checkpoint
  io::ReplayCounts copied;   ///< what the new result file got from the checkpoint's copy
};

/// The checkpoint's state.bin, read and checked: throws CheckpointError for a damaged file or a
/// checkpoint of another scenario, domain, instant or kind.
core::StateReader read_domain_checkpoint(const DomainCheckpointSite& site, std::int64_t ticks);

/// After solver.initialize() and before the first sample into a new result file: restores the
/// solver, then `extra` (the caller's records), the recorder's schedule, and copies the rows and
/// field states before the checkpoint from its copy of the result file; prints "<prefix>:
/// restarted from the checkpoint at t = ... s (cycle ...; ... history rows and ... field states
/// kept)". Throws CheckpointError as read_domain_checkpoint.
DomainRestored restore_domain_checkpoint(
    const DomainCheckpointSite& site, std::int64_t ticks, double time_s, DomainRecorder& recorder,
    integration::Solver& solver, const std::function<void(const core::StateReader&)>& extra = {});

}  // namespace crashlink::run
