#pragma once
// crashlink-coordinator (docs/design.md §1, §2.6, §2.7, §3): a message pump around its coupling
// scheme (coordinator_scheme.h, by name from coordinator_schemes.h). It binds a CoordinatorLink,
// admits one daemon per non-empty domain of the scheme's cut (admission.h), has the scheme plan
// the steps and send the Setups, then hands each message to the scheme until every daemon has said
// Bye, watching for silence, stalls and stop requests.
//
// Output: DIR/coordinator.h5 (coupling_history.h): the interface histories and /timing; the
// coordinator's checkpoints (coordinator_checkpoints.h).
//
// Failures (exit codes: core/exit_codes.h; coordinator_stops.h): a daemon that reports an Error,
// dies, goes silent for the peer timeout, breaks the protocol or registers a mismatching
// interface; a domain absent at the join timeout. Every other daemon is sent an Error naming the
// culprit, the file is written, and the result names the culprit. Bytes that are not protocol
// messages and refused Hellos are answered and logged; the run goes on.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "coupling/coupling_config.h"
#include "coupling/ticks.h"
#include "transport/session.h"

namespace crashlink::coordinator {

struct CoordinatorOptions {
  std::string bind;  ///< endpoint to bind: tcp://127.0.0.1:* (port read back), ipc://, inproc://
  std::string scenario;  ///< scenario file (daemons must run the same content: hash checked)
  std::string out_dir = "out";
  /// How the run couples (coupling/coupling_config.h): the scheme, split or multi, steps,
  /// checkpoints, restart, lanes, tick; checked by validate() (coordinator_schemes.h).
  coupling::CouplingConfig run;
  std::string endpoint_file;  ///< not empty: the bound endpoint is written there (atomically)
  transport::SessionOptions session;
  std::chrono::milliseconds join_timeout{60000};  ///< every domain joined and registered by then
  /// Called once bound, with the real endpoint (in-process launcher and tests).
  std::function<void(const std::string&)> on_bound;
  /// Called as the run goes: the time reached by the slowest domain, the end time [s] and that
  /// domain's name.
  std::function<void(double, double, const std::string&)> on_progress;
  /// Set from outside (signal handler, launcher) to stop the run: every daemon gets an Error.
  const std::atomic<bool>* stop = nullptr;
  bool in_process = false;  ///< a thread of a bigger process: CPU time of this thread only
  std::FILE* log = stderr;  ///< notices (refused peers, garbage), one line each; nullptr: none
};

/// What one daemon reported in its Bye (zeros if it did not say Bye).
struct DomainOutcome {
  std::string name;
  bool finished = false;  ///< said Bye
  double cpu_seconds = 0.0;
  double wait_seconds = 0.0;
  double wall_seconds = 0.0;
  std::int64_t cycles = 0;
  double dt_min_s = 0.0;
  std::int64_t elements = 0;
  std::int64_t step_ticks = 0;  ///< the fixed step it was given (0 before the Setup)
};

struct CoordinatorResult {
  int exit_code = 0;    ///< core/exit_codes.h
  std::string message;  ///< empty on success; else what happened, naming the culprit
  std::string culprit;  ///< the domain that failed, if known
  std::string endpoint;
  std::string coordinator_h5;
  double cpu_seconds = 0.0;
  double wall_seconds = 0.0;
  std::int64_t messages_forwarded = 0;         ///< layer vectors routed (0 over lanes)
  bool lanes = false;                          ///< the layer vectors went daemon to daemon
  std::int64_t reports = 0;                    ///< LayerReports received
  std::int64_t notices = 0;                    ///< refused or dropped messages logged
  std::int64_t checkpoint_interval_ticks = 0;  ///< the interval used (0: none)
  std::int64_t restarted_from_ticks = -1;      ///< the checkpoint resumed from (-1: from t = 0)
  std::vector<DomainOutcome> domains;
};

/// Runs the coordinator to the end of the run (or the first failure). Never throws.
CoordinatorResult run_coordinator(const CoordinatorOptions& options);

}  // namespace crashlink::coordinator
