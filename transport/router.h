#pragma once
// Coordinator side of the wire (DESIGN.md §3): a ZeroMQ ROUTER bound to one endpoint, one
// Envelope per ZeroMQ message, addressed by the peer's routing id (a daemon's domain name).
// - ROUTER_MANDATORY: a send to a peer that is not connected throws TransportError instead of
//   being dropped silently.
// - receive() always has a timeout; bytes that are not an Envelope come back as a Received with
//   error() set and the peer named, never as a crash.
// One thread at a time (ZeroMQ sockets are not thread-safe); movable, not copyable.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"
#include "transport/received.h"
#include "transport/socket_options.h"

namespace crashlink::transport {

class Router {
 public:
  /// Binds `endpoint` (parse_endpoint(…, Use::bind)); an ephemeral tcp port is resolved and
  /// endpoint() returns the real one. Throws TransportError (endpoint in use, bad address, ...).
  explicit Router(std::string_view endpoint, const SocketOptions& options = {});
  ~Router();
  Router(Router&&) noexcept;
  Router& operator=(Router&&) noexcept;

  /// The endpoint daemons connect to, read back with ZMQ_LAST_ENDPOINT
  /// (tcp://127.0.0.1:* -> tcp://127.0.0.1:40123).
  const std::string& endpoint() const;

  /// Sends one Envelope to `peer` (routing id). Throws TransportError if the peer is not
  /// connected (EHOSTUNREACH) or its queue stays full for SocketOptions::send_timeout_ms.
  void send(std::string_view peer, const wire::Envelope& envelope);
  /// As send(), but never waits: returns false when the peer's queue is full (for heartbeats).
  bool try_send(std::string_view peer, const wire::Envelope& envelope);
  /// As send(), for a message received earlier (Received::payload): its bytes go to `peer` as they
  /// came, without serialising again or copying; `payload` is left empty. Throws TransportError
  /// as send(), and std::invalid_argument for an empty payload.
  void forward(std::string_view peer, Payload&& payload);

  /// The next message, or nullopt after `timeout` with none (0: do not wait). A parsed message
  /// keeps its bytes in Received::payload (for forward()).
  std::optional<Received> receive(std::chrono::milliseconds timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::transport
