#pragma once
// The one set of defaults of the options that `crashlink run`, crashlink-solver and
// crashlink-coordinator share (docs/processes.md, "Options"). Every program's flag definitions
// take their defaults from here, so that a run started by hand (README, "Running on several
// hosts") gets what `crashlink run` passes on to the processes it starts: before, the daemon's
// --step-safety defaulted to 1 and `crashlink run`'s to 0.9, and the by-hand run of the CI scene
// stopped at 3.56 ms where `crashlink run` finished.
//
// The library structs (daemon::DaemonOptions, coordinator::CoordinatorOptions,
// transport::SessionOptions) keep their own defaults for in-process callers and tests.
namespace crashlink::apps {

struct SharedDefaults {
  /// --out DIR (all three).
  static constexpr const char* out = "out";
  /// --coupling (all three).
  static constexpr const char* coupling = "layer";
  /// --mode of the coordinator; `crashlink run --mode` also has `mono`, its own default.
  static constexpr const char* coupled_mode = "multi";
  /// --step-safety (`crashlink run`, crashlink-solver, `crashlink advise`): the factor on each
  /// domain's initial stable step before the steps are fixed for the run (the stable step
  /// shrinks as the mesh deforms; a fixed step above it stops the run).
  static constexpr double step_safety = 0.9;
  /// --join-timeout-ms (`crashlink run`, crashlink-coordinator).
  static constexpr int join_timeout_ms = 60000;
  /// --checkpoint-interval S (`crashlink run`, crashlink-coordinator): 0, none.
  static constexpr double checkpoint_interval_s = 0.0;
  /// --heartbeat-ms, --timeout-ms, --handshake-timeout-ms (all three; apps/session_flags.h).
  static constexpr int heartbeat_ms = 500;
  static constexpr int peer_timeout_ms = 5000;
  static constexpr int handshake_timeout_ms = 30000;
};

}  // namespace crashlink::apps
