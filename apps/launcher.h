#pragma once
// `crashlink run --mode split|multi` on one machine (docs/design.md §1, §4; docs/processes.md): the
// coordinator and one daemon per non-empty domain, as processes (ipc or tcp) or as threads of
// this process (inproc).
//
// Processes: crashlink-coordinator and crashlink-solver are the executables beside this one
// (/proc/self/exe). The coordinator binds ipc://DIR/coordinator.sock (a path under $TMPDIR if DIR
// is too long for a Unix socket) or tcp://127.0.0.1:* and writes the real endpoint to
// DIR/coordinator.endpoint; the launcher reads it back, starts the daemons with --connect, and
// waits. Children die with the launcher (PR_SET_PDEATHSIG). When one of them fails, the others
// get the coordinator's own failure handling (peer timeout + heartbeat + 2 s) to stop by
// themselves; whoever is still running then gets SIGTERM (it tells its peers and writes its
// file), and SIGKILL 2 s later.
// Threads (inproc): the same run_coordinator / run_daemon on one ZeroMQ context; they stop by
// their own timeouts only.
#include <string>
#include <vector>

#include "apps/session_flags.h"
#include "apps/shared_defaults.h"
#include "coupling/coupling_config.h"
#include "transport/endpoint.h"

namespace crashlink::apps {

struct LaunchOptions {
  std::string scenario;
  std::string out_dir;
  /// How the run couples (coupling/coupling_config.h), for the coordinator and every daemon.
  coupling::CouplingConfig run;
  transport::Scheme scheme = transport::Scheme::ipc;
  bool progress = true;  ///< the coordinator's progress line on stderr
  SessionFlags session;
  int join_timeout_ms = SharedDefaults::join_timeout_ms;
  double step_safety = SharedDefaults::step_safety;  ///< to every daemon (--step-safety)
  int threads = 1;  ///< to every daemon (--threads): each domain's solver threads
  /// Per domain, in the order of the launch's domains (empty: `threads` for every one).
  std::vector<int> domain_threads;
  /// The threads of the k-th domain of the launch.
  int threads_of(std::size_t k) const {
    return k < domain_threads.size() ? domain_threads[k] : threads;
  }
};

/// How one piece of the run ended.
struct PieceOutcome {
  std::string name;    ///< "coordinator" or the domain name
  int exit_code = -1;  ///< the exit code; -1 if killed by a signal or never started
  int signal = 0;      ///< the signal that ended it, if any
  bool killed_by_launcher = false;
  std::string message;       ///< inproc: the piece's own error message
  double cpu_seconds = 0.0;  ///< processes: from wait4's rusage; inproc: the thread's
  bool ok() const { return exit_code == 0; }
  std::string describe() const;
};

struct LaunchResult {
  std::vector<PieceOutcome> pieces;  ///< coordinator first, then the domains in order
  std::string endpoint;
  double wall_seconds = 0.0;
  /// SIGINT or SIGTERM came while a piece was still running: every piece was told to stop at
  /// once; the run counts as stopped whatever the pieces' exit codes (kExitStopped).
  bool stopped_on_request = false;
  bool ok() const;
};

/// Runs the pieces to the end. Throws InputError when an executable is missing or the
/// coordinator does not come up (its endpoint file does not appear within the join timeout).
LaunchResult launch_local(const LaunchOptions& options, const std::vector<std::string>& domains);

}  // namespace crashlink::apps
