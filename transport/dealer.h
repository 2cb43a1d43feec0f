#pragma once
// Daemon side of the wire (docs/design.md §3): a ZeroMQ DEALER connected to the coordinator's
// ROUTER, routing id = the session's name ("<domain>#<random>", DaemonLink; a lane's: the domain),
// one Envelope per ZeroMQ message. Connecting never blocks (ZeroMQ connects and reconnects in the
// background); receive() always has a timeout; bytes that are not an Envelope come back as a
// Received with error() set. CURVE (curve_policy.h): on any non-loopback tcp endpoint, or when
// SocketOptions::curve.force, the Dealer is a CURVE client; over tcp and ipc a socket monitor
// watches the security handshake and receive() throws CurveRefusedError as soon as the
// coordinator refuses it (key not authorised, wrong server key, CURVE on one side only).
// One thread at a time; movable, not copyable.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"
#include "transport/received.h"
#include "transport/socket_options.h"

namespace crashlink::transport {

class Dealer {
 public:
  /// Connects to `endpoint` (parse_endpoint(…, Use::connect)) as `routing_id` (1-255 bytes, not
  /// starting with a zero byte; a session's is "<domain>#<random>", and messages name the domain:
  /// the routing id up to its first '#'). Throws TransportError; with CURVE on, CurveConfigError or
  /// CurveKeyFileError (a key missing or unusable).
  Dealer(std::string_view endpoint, std::string_view routing_id, const SocketOptions& options = {});
  ~Dealer();
  Dealer(Dealer&&) noexcept;
  Dealer& operator=(Dealer&&) noexcept;

  const std::string& endpoint() const;
  const std::string& routing_id() const;
  /// Whether this Dealer is a CURVE client.
  bool curve() const;

  /// Queues one Envelope for the coordinator. Throws TransportError if the queue stays full for
  /// SocketOptions::send_timeout_ms.
  void send(const wire::Envelope& envelope);
  /// As send(), but never waits: returns false when the message cannot be queued now (queue
  /// full, or no connection to queue on: inproc after the coordinator closed). For heartbeats.
  bool try_send(const wire::Envelope& envelope);
  /// Queues arbitrary bytes as one message: for tests and diagnostics tools only.
  void send_raw(std::string_view bytes);

  /// The next message, or nullopt after `timeout` with none (0: do not wait). Throws
  /// CurveRefusedError when the coordinator has refused the security handshake.
  std::optional<Received> receive(std::chrono::milliseconds timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::transport
