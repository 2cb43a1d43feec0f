#pragma once
// Protocol layer over the sockets (docs/design.md §3, §7 rule 2): the session rules both links
// share.
//   daemon Hello(protocol_version, scenario_hash, domain, role) -> coordinator Hello, or Error
//   with the reason, both values and the fix; then application messages both ways; a Heartbeat
//   from either side when it has sent nothing for heartbeat_interval; a peer that has sent
//   nothing at all for peer_timeout is dead; Bye ends a session cleanly, Error ends it loudly.
// coordinator_link.h and daemon_link.h implement the two ends.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"
#include "transport/socket_options.h"

namespace crashlink::transport {

struct SessionOptions {
  /// Send a Heartbeat when nothing was sent to a peer for this long
  /// (Options.heartbeat_interval_ms).
  std::chrono::milliseconds heartbeat_interval{500};
  /// A peer that sent nothing for this long is dead (Options.peer_timeout_ms).
  std::chrono::milliseconds peer_timeout{5000};
  /// Daemon: how long to wait for the coordinator's answer to its Hello (the coordinator may start
  /// after the daemons).
  std::chrono::milliseconds handshake_timeout{10000};
  /// Polled at least every 100 ms while a daemon waits for the answer to its Hello; set (by a
  /// SIGINT / SIGTERM handler): the wait ends with StopRequested. Not owned; may be null.
  const std::atomic<bool>* stop = nullptr;
  SocketOptions socket;

  /// Throws TransportError (naming `endpoint`) unless 0 < heartbeat_interval < peer_timeout and
  /// handshake_timeout > 0.
  void validate(std::string_view endpoint) const;
};

/// A daemon's Hello: this build's kProtocolVersion, role daemon.
wire::Hello daemon_hello(std::string_view domain, std::string_view scenario_hash);

/// The coordinator's checks of a daemon's Hello, in this order: role, protocol version, scenario
/// hash, domain known. Returns the Error to send back (code, message with both values and the
/// fix, domain; the peer's strings escaped, core::log_escape), or nullopt to accept. Whether the
/// domain is free is the link's check (CoordinatorLink: ERROR_CODE_DOMAIN_HELD).
std::optional<wire::Error> check_hello(const wire::Hello& hello, std::string_view scenario_hash,
                                       std::span<const std::string> domains);

/// An Envelope holding `message` (one of the wire messages).
wire::Envelope make_error(wire::ErrorCode code, std::string message, std::string domain = {});
wire::Envelope make_bye(std::string reason);

}  // namespace crashlink::transport
