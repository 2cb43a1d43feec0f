#pragma once
// Where a process's CURVE keys are (docs/processes.md, "Security (CURVE)"), part of
// SocketOptions. The coordinator is the CURVE server (its own secret key, the daemons' public
// keys in an authorized-keys file checked by the ZAP handler, zap_handler.h); a daemon is a
// CURVE client (its own secret key, the coordinator's public key). curve_policy.h says when
// CURVE is on; the command-line flags and environment variables below fill these fields
// (apps/session_flags.h).
#include <string>

namespace crashlink::transport {

struct CurveOptions {
  /// Use CURVE on loopback tcp and ipc too (always on for any other tcp address; never on
  /// inproc, whose bytes never leave the process). --curve, CRASHLINK_CURVE=1.
  bool force = false;
  /// This process's secret key (`crashlink keygen` PREFIX.key). --curve-secret-key,
  /// CRASHLINK_CURVE_SECRET_KEY_FILE.
  std::string secret_key_file;
  /// Daemon: the coordinator's public key (its PREFIX.pub). --curve-server-key,
  /// CRASHLINK_CURVE_SERVER_KEY_FILE.
  std::string server_key_file;
  /// Coordinator: the daemons' public keys, one per line. --curve-authorized-keys,
  /// CRASHLINK_CURVE_AUTHORIZED_KEYS_FILE.
  std::string authorized_keys_file;

  // In memory, for a daemon's lane (docs/processes.md "Lanes"), whose keys come from the
  // coordinator's Setup rather than from files:
  /// Client: the server's public key (Z85); replaces server_key_file when not empty.
  std::string server_key;
  /// Server: no authorized-keys file; the keys come later (Router::authorize). A client that
  /// connects before then waits for them (up to 10 s) instead of being refused.
  bool authorize_later = false;
};

inline constexpr const char* kCurveEnv = "CRASHLINK_CURVE";
inline constexpr const char* kCurveSecretKeyEnv = "CRASHLINK_CURVE_SECRET_KEY_FILE";
inline constexpr const char* kCurveServerKeyEnv = "CRASHLINK_CURVE_SERVER_KEY_FILE";
inline constexpr const char* kCurveAuthorizedKeysEnv = "CRASHLINK_CURVE_AUTHORIZED_KEYS_FILE";

}  // namespace crashlink::transport
