#pragma once
// Coordinator side of the wire (docs/design.md §3): a ZeroMQ ROUTER bound to one endpoint, one
// Envelope per ZeroMQ message, addressed by the peer's routing id (a daemon's domain name).
// - ROUTER_MANDATORY: a send to a peer that is not connected throws TransportError instead of
//   being dropped silently.
// - ROUTER_HANDOVER: a peer connecting with the routing id of a connection the ROUTER still holds
//   (closing, or half-open) takes the id over and the old connection is dropped; without it the
//   new connection would be ignored until its handshake timeout (bench_handshake_soak).
// - receive() always has a timeout; bytes that are not an Envelope come back as a Received with
//   error() set and the peer named, never as a crash.
// - CURVE (curve_policy.h): on any non-loopback tcp endpoint, or when SocketOptions::curve.force,
//   the Router is a CURVE server whose clients' keys the process's ZAP handler checks against
//   the authorized keys (zap_handler.h); refused clients are kept for take_refusals().
// One thread at a time (ZeroMQ sockets are not thread-safe); movable, not copyable.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "proto/crashlink.pb.h"
#include "transport/received.h"
#include "transport/socket_options.h"
#include "transport/zap_handler.h"

namespace crashlink::transport {

class Router {
 public:
  /// Binds `endpoint` (parse_endpoint(…, Use::bind)); an ephemeral tcp port is resolved and
  /// endpoint() returns the real one. Throws TransportError (endpoint in use, bad address, ...);
  /// with CURVE on, CurveConfigError or CurveKeyFileError (a key missing or unusable).
  explicit Router(std::string_view endpoint, const SocketOptions& options = {});
  ~Router();
  Router(Router&&) noexcept;
  Router& operator=(Router&&) noexcept;

  /// The endpoint daemons connect to, read back with ZMQ_LAST_ENDPOINT
  /// (tcp://127.0.0.1:* -> tcp://127.0.0.1:40123).
  const std::string& endpoint() const;

  /// Whether this Router is a CURVE server.
  bool curve() const;
  /// CURVE server: its public key (Z85), "" otherwise.
  const std::string& curve_public_key() const;
  /// CURVE server bound with CurveOptions::authorize_later: the clients' keys it accepts from now
  /// (a daemon's lane: its partners', from the Setup). No effect without CURVE.
  void authorize(std::vector<std::string> keys);
  /// The CURVE clients refused since the last call (unauthorised key, wrong server key, no
  /// CURVE), each with a text naming the key or the endpoint and the fix; never waits.
  std::vector<CurveRefusal> take_refusals();

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
