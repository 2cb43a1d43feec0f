#pragma once
// crashlink-solver: one domain of a coupled run (docs/design.md §1, §3) as a daemon talking to the
// coordinator over a DaemonLink (transport/daemon_link.h): a message pump between its transport
// and its coupling scheme (coupling/domain_scheme.h, found by name in domain_schemes.h), which
// decides what is sent, what is awaited and when a cycle runs. The session step by step (Hello,
// Register, Setup, the run, Bye) is docs/processes.md "The session"; the lanes
// (daemon_lanes.h) docs/processes.md "Lanes: the layer vectors daemon to daemon".
//
// Output: DIR/domains/<domain>.h5 and .xdmf (domain_output.h), what solver/gather reads back.
// Failures (core/exit_codes.h, docs/processes.md "Failures"): what ends the daemon is reported to
// the coordinator as an Error naming the domain, the time and the cycle, unless the coordinator
// is the one who stopped it; the result file is flushed and closed in every case.
#include <atomic>
#include <cstdint>
#include <string>

#include "transport/session.h"

namespace crashlink::daemon {

struct DaemonOptions {
  std::string endpoint;  ///< the coordinator's (tcp://host:port, ipc://path, inproc://name)
  std::string domain;    ///< the domain this daemon runs (the scenario's `domains:` name)
  std::string scenario;  ///< scenario file (the same content as the coordinator's)
  std::string out_dir = "out";
  transport::SessionOptions session;  ///< heartbeat interval, peer and handshake timeouts
  /// Step proposal sent in Register: floor(step_safety * min(dt, max_step_s) * ticks_per_second),
  /// dt the solver's initial stable step (LayerNetworkOptions' rule, so both plan the same steps).
  double step_safety = 1.0;
  double max_step_s = 0.0;  ///< > 0: caps the proposal (how tests and studies impose a ratio)
  /// Offer a lane to the partners when the scheme has vectors for them (docs/processes.md
  /// "Lanes"); false: --no-lane, this domain's vectors (and so every domain's) go through the
  /// coordinator.
  bool offer_lane = true;
  /// The coupling scheme (crashlink-solver --coupling; domain_schemes.h): how the scenario is cut
  /// and what travels each cycle. The coordinator's Setup must name the same.
  std::string coupling = "layer";
  /// Run as a thread of a bigger process (crashlink run --transport inproc): CPU time is this
  /// thread's, not the process's.
  bool in_process = false;
  /// Threads computing this domain's element forces (crashlink-solver --threads; >= 1).
  int threads = 1;
  /// Set from outside (signal handler) to stop: checked every cycle; the coordinator is told.
  const std::atomic<bool>* stop = nullptr;
};

struct DaemonResult {
  int exit_code = 0;    ///< core/exit_codes.h
  std::string message;  ///< empty on success; else what happened (names the domain)
  std::string result_h5;
  std::int64_t cycles = 0;
  double cpu_seconds = 0.0;
  double wait_seconds = 0.0;
  double wall_seconds = 0.0;
};

/// Runs the daemon to the end (or the first failure). Never throws.
DaemonResult run_daemon(const DaemonOptions& options);

}  // namespace crashlink::daemon
