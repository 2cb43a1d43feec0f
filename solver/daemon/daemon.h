#pragma once
// crashlink-solver: one domain of a coupled run (docs/design.md §1, §2.7, §3) as a daemon talking
// to the coordinator over a DaemonLink (transport/daemon_link.h): a message pump between its
// transport and its coupling scheme (coupling/domain_scheme.h; `layer` or `paper`,
// domain_schemes.h), which decides what is sent, what is awaited and when a cycle runs. Below,
// what a `layer` run does (`paper`: Register of the coupled nodes, then per cycle FreeState ->
// Correction, docs/design.md §2.6; no lanes, no checkpoints, no reports).
//
//   read the scenario, hash it (io::scenario_hash: the coordinator refuses another file),
//   cut it (partition::decompose, Layer), build this domain (cosim::build_layer_domain),
//   Solver::initialize(), open DIR/domains/<domain>.h5,
//   connect: Hello (protocol version, scenario hash, domain) -> the coordinator's Hello,
//   open this daemon's lane (transport/lane_endpoint.h: shared memory beside an ipc session, a
//     ZeroMQ ROUTER otherwise, CURVE across hosts; docs/processes.md "Lanes"),
//   Register: per interface its J node ids, masses (owner: J's natural summed mass, ghost
//     holder: 0) and positions; the initial stable step floor(min(dt, max_step) * safety * tps);
//     the lane,
//   Setup: this domain's fixed step, every partner's step and, when every daemon offered one,
//     the partners' lanes,
//   cosim::LayerStepper: advance(); each message it produces leaves as soon as it is queued
//     (LayerStepper::set_on_outbox: u_J(T + H) before the coarse side's nodal passes, so the
//     domains compute at the same time) as LayerDisplacement / LayerForce, on the partner's lane or
//     to the coordinator; when it waits, block on its lane (polling the session every 20 ms) or on
//     the link, and deliver(); keep_alive() every cycle; a LayerReport (the instant, the fine
//     side's interface history rows) every quarter heartbeat interval and before a checkpoint,
//   at the end: a last field state, /timing, a LayerReport, Bye with a DomainReport (CPU, wait,
//     cycles).
//
// Output: DIR/domains/<domain>.h5 and .xdmf (io::ResultWriter layout, the domain's sub-model,
// sampled at the instants a mono run samples: run/domain_recorder.h), what solver/gather reads.
//
// Failures (exit codes: core/exit_codes.h): a guard failure (NumericalError), a model error,
// a protocol violation or an internal error is reported to the coordinator as an Error (code, and a
// message naming the domain, the time and the cycle); an Error from the coordinator, a silent
// coordinator (PeerTimeoutError) or a socket failure ends the daemon. In every case the result
// file is flushed and closed (what was sampled stays readable) and run_daemon returns non-zero.
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
