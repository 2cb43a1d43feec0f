#pragma once
// `crashlink run SCENARIO [--out DIR] [--mode mono|split|multi] [--coupling layer|paper]
// [--transport ipc|tcp|inproc] [--quiet] [--heartbeat-ms N] [--timeout-ms N]
// [--join-timeout-ms N] [--step-safety F] [--reference mono] [--checkpoint-interval S]
// [--restart DIR]` (docs/design.md §4): runs the scenario,
// shows progress, prints the summary and, for every probe on a rigid body (a headform), HIC15 and
// HIC36 after CFC 1000 (the same output as `crashlink hic DIR/result.h5 --probe NAME`). The
// modes and options: run_run.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "apps/session_flags.h"
#include "apps/shared_defaults.h"

namespace crashlink::apps {

struct RunCommandOptions {
  std::string scenario;
  std::string out = SharedDefaults::out;
  std::string mode = "mono";
  std::string coupling = SharedDefaults::coupling;
  std::string transport = "ipc";
  bool quiet = false;
  SessionFlags session;
  int join_timeout_ms = SharedDefaults::join_timeout_ms;
  /// split/multi: factor on every domain's initial stable step before the steps are fixed for
  /// the run (the stable step shrinks as the mesh deforms; a fixed step above it stops the run).
  double step_safety = SharedDefaults::step_safety;
  /// "" or "mono": run the reference too and compare (split/multi only).
  std::string reference;
  /// checkpoints every this much simulated time [s] (0: none).
  double checkpoint_interval_s = SharedDefaults::checkpoint_interval_s;
  /// resume the run in this folder from its newest complete checkpoint (--out).
  std::string restart;
  bool no_lanes = false;  ///< CoordinatorOptions::lanes = false
  /// Threads per solver (0: every core this process may use; docs/threads.md).
  int threads = 1;
  /// split/multi: NAME=N per domain (--domain-threads), before --threads.
  std::vector<std::string> domain_threads;
  /// --reference mono: the reference's threads (0: every core this process may use; the fair
  /// wall-clock comparison runs it on as many cores as the coupled run uses).
  int reference_threads = 1;
  bool no_drift = false;        ///< `paper`: drift correction [11] off
  bool variable_steps = false;  ///< each domain follows its own step (docs/design.md §2.6)
  /// A keyword deck's unit system (deck/units.h); required for a deck, refused for YAML.
  std::string units;
  /// A deck's keywords to skip (--ignore K1,K2), each printed with its card count.
  std::vector<std::string> ignore;
};

CLI::App* add_run_command(CLI::App& app, RunCommandOptions& options);

/// Runs the command:
///   mono: the whole model in this process (run/run_single.h).
///   split | multi: the coordinator and one daemon per domain (apps/launcher.h), then the results
///     gathered into DIR/result.h5; the summary adds the coordinator's share of the CPU time and
///     the wall time against the sum of the CPU times.
///   --reference mono (split | multi only): afterwards, the same scene in `mono` into
///     DIR/reference/, then the paper's Table 1 of the two (`crashlink compare`, cmd_compare.h).
///   --checkpoint-interval S: checkpoints of every process (mono: of the run) every S of
///     simulated time in DIR/checkpoints; --restart DIR resumes the run in DIR from the newest
///     one every process has, and ends as the uninterrupted run would have (docs/checkpoints.md).
///   SCENARIO may be a keyword deck (.k, .key, .dyn, .kw) with --units SYSTEM [--ignore K1,K2]:
///     mono; split and multi take a scenario YAML naming the deck with its domains
///     (`model: {deck: model.k, units: ...}`, docs/decks.md "In a scenario").
/// Returns the exit code (core/exit_codes.h): 0; 3 when the guard stopped the run (output
/// kept); split/multi: 5 when a process failed (the message names it). Input errors throw.
int run_run(const RunCommandOptions& options);

/// split / multi (cmd_run_coupled.cpp).
int run_coupled(const RunCommandOptions& options);

}  // namespace crashlink::apps
