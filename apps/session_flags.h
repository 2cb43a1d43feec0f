#pragma once
// Command-line flags for the liveness settings of a session (transport/session.h), shared by
// `crashlink run`, crashlink-solver and crashlink-coordinator (docs/processes.md). Every process
// of one run should get the same values (the launcher passes them on).
#include <CLI/CLI.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "transport/session.h"

namespace crashlink::apps {

struct SessionFlags {
  int heartbeat_ms = 500;            ///< send a Heartbeat after this much silence
  int peer_timeout_ms = 5000;        ///< a peer silent this long is dead
  int handshake_timeout_ms = 30000;  ///< daemon: wait this long for the coordinator's Hello

  transport::SessionOptions options() const {
    transport::SessionOptions o;
    o.heartbeat_interval = std::chrono::milliseconds{heartbeat_ms};
    o.peer_timeout = std::chrono::milliseconds{peer_timeout_ms};
    o.handshake_timeout = std::chrono::milliseconds{handshake_timeout_ms};
    return o;
  }

  /// The same flags for a child process.
  std::vector<std::string> arguments() const {
    return {"--heartbeat-ms",         std::to_string(heartbeat_ms),
            "--timeout-ms",           std::to_string(peer_timeout_ms),
            "--handshake-timeout-ms", std::to_string(handshake_timeout_ms)};
  }
};

inline void add_session_flags(CLI::App& app, SessionFlags& f) {
  app.add_option("--heartbeat-ms", f.heartbeat_ms,
                 "heartbeat interval, ms (a Heartbeat after this much silence)")
      ->check(CLI::Range(1, 3600000))
      ->capture_default_str();
  app.add_option("--timeout-ms", f.peer_timeout_ms,
                 "peer timeout, ms: a peer silent this long is dead and the run stops")
      ->check(CLI::Range(2, 3600000))
      ->capture_default_str();
  app.add_option("--handshake-timeout-ms", f.handshake_timeout_ms,
                 "daemon: how long to wait for the coordinator's answer to its Hello, ms")
      ->check(CLI::Range(1, 3600000))
      ->capture_default_str();
}

}  // namespace crashlink::apps
