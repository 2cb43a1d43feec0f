#pragma once
// Command-line flags for the liveness settings of a session (transport/session.h), shared by
// `crashlink run`, crashlink-solver and crashlink-coordinator (docs/processes.md). Every process
// of one run should get the same values (the launcher passes them on). The CURVE flags
// (transport/curve_options.h) default to their CRASHLINK_CURVE_* environment variables.
#include <CLI/CLI.hpp>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "apps/shared_defaults.h"
#include "transport/session.h"

namespace crashlink::apps {

struct SessionFlags {
  int heartbeat_ms = SharedDefaults::heartbeat_ms;  ///< send a Heartbeat after this much silence
  int peer_timeout_ms = SharedDefaults::peer_timeout_ms;  ///< a peer silent this long is dead
  /// daemon: wait this long for the coordinator's Hello
  int handshake_timeout_ms = SharedDefaults::handshake_timeout_ms;
  transport::CurveOptions curve;  ///< CURVE keys (docs/processes.md, "Security (CURVE)")

  transport::SessionOptions options() const {
    transport::SessionOptions o;
    o.heartbeat_interval = std::chrono::milliseconds{heartbeat_ms};
    o.peer_timeout = std::chrono::milliseconds{peer_timeout_ms};
    o.handshake_timeout = std::chrono::milliseconds{handshake_timeout_ms};
    o.socket.curve = curve;
    return o;
  }

  /// The same flags for a child process.
  std::vector<std::string> arguments() const {
    std::vector<std::string> a = {"--heartbeat-ms",         std::to_string(heartbeat_ms),
                                  "--timeout-ms",           std::to_string(peer_timeout_ms),
                                  "--handshake-timeout-ms", std::to_string(handshake_timeout_ms)};
    if (curve.force) a.emplace_back("--curve");
    const std::pair<const char*, const std::string*> files[] = {
        {"--curve-secret-key", &curve.secret_key_file},
        {"--curve-server-key", &curve.server_key_file},
        {"--curve-authorized-keys", &curve.authorized_keys_file}};
    for (const auto& [flag, file] : files) {
      if (file->empty()) continue;
      a.emplace_back(flag);
      a.push_back(*file);
    }
    return a;
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
  app.add_flag("--curve", f.curve.force,
               "CURVE authentication and encryption on loopback tcp and ipc too (always on for "
               "other tcp endpoints)")
      ->envname(transport::kCurveEnv);
  app.add_option("--curve-secret-key", f.curve.secret_key_file,
                 "this process's CURVE secret key file (crashlink keygen: PREFIX.key)")
      ->envname(transport::kCurveSecretKeyEnv);
  app.add_option("--curve-server-key", f.curve.server_key_file,
                 "daemon: the coordinator's CURVE public key file (its PREFIX.pub)")
      ->envname(transport::kCurveServerKeyEnv);
  app.add_option("--curve-authorized-keys", f.curve.authorized_keys_file,
                 "coordinator: the daemons' CURVE public keys, one per line ('#' comments)")
      ->envname(transport::kCurveAuthorizedKeysEnv);
}

}  // namespace crashlink::apps
