#include "transport/router.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "transport/curve_policy.h"
#include "transport/curve_support.h"
#include "transport/detail/handshake_monitor.h"
#include "transport/detail/zmq.h"
#include "transport/endpoint.h"
#include "transport/errors.h"
#include "transport/zap_handler.h"

namespace crashlink::transport {

struct Router::Impl {
  // Declared first, so destroyed last: no handshake can reach a stopped ZAP handler (libzmq
  // accepts every client when no handler is bound).
  std::unique_ptr<ZapDomain> zap;
  zmq::socket_t socket;
  std::string endpoint;
  std::vector<zmq::message_t> frames;
  std::string public_key;                           // CURVE: ours, for the messages
  std::optional<detail::HandshakeMonitor> monitor;  // CURVE: failed handshakes, for the log

  /// CURVE server: our secret key, the ZAP domain with the authorized keys, the monitor.
  void secure(const Endpoint& parsed, const CurveServerKeys& keys);

  /// False when the first frame cannot be queued (EAGAIN: queue full, after the send timeout if
  /// `wait` is none); throws TransportError for an unknown peer. `payload` is consumed when sent.
  bool send(std::string_view peer, zmq::message_t& payload, zmq::send_flags wait);
};

Router::Router(std::string_view endpoint, const SocketOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const Endpoint parsed = parse_endpoint(endpoint, Use::bind);
  try {
    impl_->socket = zmq::socket_t(detail::process_context(), zmq::socket_type::router);
    detail::configure(impl_->socket, options);
    impl_->socket.set(zmq::sockopt::router_mandatory, true);
    // A new connection with the routing id of one not yet torn down (a refused daemon restarted
    // at once) takes the id over; without this ZeroMQ ignores it and its Hello goes unanswered.
    impl_->socket.set(zmq::sockopt::router_handover, true);
    if (auto keys = curve_server_keys(parsed, options.curve)) impl_->secure(parsed, *keys);
    impl_->socket.bind(parsed.text);
    impl_->endpoint = impl_->socket.get(zmq::sockopt::last_endpoint);
  } catch (const zmq::error_t& e) {
    throw TransportError(parsed.text, fmt::format("cannot bind: {} (errno {}); is the endpoint "
                                                  "in use by another run or not a local address?",
                                                  e.what(), e.num()));
  }
}

void Router::Impl::secure(const Endpoint& parsed, const CurveServerKeys& keys) {
  require_curve(fmt::format("the coordinator's endpoint {}", parsed.text));
  zap = std::make_unique<ZapDomain>(keys.authorized, keys.authorized_file, keys.authorize_later);
  public_key = keys.public_key;
  socket.set(zmq::sockopt::curve_server, true);
  socket.set(zmq::sockopt::curve_secretkey, keys.secret_key);
  socket.set(zmq::sockopt::zap_domain, zap->name());
  monitor.emplace(socket, ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL);
}

Router::~Router() = default;
Router::Router(Router&&) noexcept = default;
Router& Router::operator=(Router&&) noexcept = default;

const std::string& Router::endpoint() const {
  return impl_->endpoint;
}

const std::string& Router::curve_public_key() const {
  return impl_->public_key;
}

void Router::authorize(std::vector<std::string> keys) {
  if (impl_->zap) impl_->zap->authorize(std::move(keys));
}

bool Router::curve() const {
  return impl_->zap != nullptr;
}

std::vector<CurveRefusal> Router::take_refusals() {
  if (!impl_->zap) return {};
  std::vector<CurveRefusal> out = impl_->zap->take_refusals();
  for (const auto& e : impl_->monitor->drain()) {
    CurveRefusal r;
    r.address = e.address;
    if (e.value == ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC) {
      r.text = fmt::format(
          "refused a CURVE connection on {}: the client's HELLO does not decrypt with this "
          "coordinator's key ({}), so that daemon was given the wrong server public key; fix: "
          "give it this coordinator's public key {} (its PREFIX.pub) as --curve-server-key",
          impl_->endpoint, detail::protocol_error_name(e.value), impl_->public_key);
    } else if (e.value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) {
      r.text = fmt::format(
          "refused a connection on {}: the client does not use CURVE ({}) and this coordinator "
          "requires it; fix: start that daemon with --curve, --curve-secret-key and "
          "--curve-server-key",
          impl_->endpoint, detail::protocol_error_name(e.value));
    } else {
      r.text = fmt::format("refused a connection on {}: the CURVE handshake failed with {}",
                           impl_->endpoint, detail::protocol_error_name(e.value));
    }
    out.push_back(std::move(r));
  }
  return out;
}

namespace {

[[noreturn]] void send_timed_out(const std::string& endpoint, std::string_view peer) {
  throw TransportError(endpoint, fmt::format("send to '{}' timed out: its queue is full (peer "
                                             "stalled or gone)",
                                             printable_peer(peer)));
}

}  // namespace

void Router::send(std::string_view peer, const wire::Envelope& envelope) {
  zmq::message_t payload = detail::serialize(envelope);
  if (!impl_->send(peer, payload, zmq::send_flags::none)) send_timed_out(impl_->endpoint, peer);
}

bool Router::try_send(std::string_view peer, const wire::Envelope& envelope) {
  zmq::message_t payload = detail::serialize(envelope);
  return impl_->send(peer, payload, zmq::send_flags::dontwait);
}

void Router::forward(std::string_view peer, Payload&& payload) {
  if (payload.empty()) throw std::invalid_argument("crashlink::transport: forward of no payload");
  const Payload taken = std::move(payload);
  if (!impl_->send(peer, taken.impl()->message, zmq::send_flags::none)) {
    send_timed_out(impl_->endpoint, peer);
  }
}

bool Router::Impl::send(std::string_view peer, zmq::message_t& payload, zmq::send_flags wait) {
  try {
    // ROUTER_MANDATORY fails the first frame for an unknown peer (EHOSTUNREACH) or a full queue
    // (EAGAIN), so nothing half-sent remains; the second frame then always queues.
    if (!socket.send(zmq::buffer(peer.data(), peer.size()), zmq::send_flags::sndmore | wait)) {
      return false;
    }
    (void)socket.send(payload, zmq::send_flags::none);
    return true;
  } catch (const zmq::error_t& e) {
    // a daemon's session id is "<domain>#<hex>": name the domain first, as the logs do
    const std::string_view domain = peer.substr(0, peer.find('#'));
    const std::string who =
        domain.size() == peer.size()
            ? fmt::format("'{}'", printable_peer(peer))
            : fmt::format("'{}' (session '{}')", printable_peer(domain), printable_peer(peer));
    if (e.num() == EHOSTUNREACH) {
      throw TransportError(endpoint,
                           fmt::format("send to {}: no such peer connected (it never connected "
                                       "or has disconnected)",
                                       who));
    }
    throw TransportError(endpoint,
                         fmt::format("send to {}: {} (errno {})", who, e.what(), e.num()));
  }
}

std::optional<Received> Router::receive(std::chrono::milliseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + timeout;
  auto& frames = impl_->frames;
  for (;;) {
    // Poll first: zmq_poll looks at the socket's pending commands before it blocks, so a message
    // already there costs no extra system call, and an empty socket no failed receive.
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (!detail::wait_readable(impl_->socket, std::max(left, std::chrono::milliseconds{0}))) {
      if (left.count() <= 0) return std::nullopt;
      continue;
    }
    frames.clear();
    std::optional<std::size_t> n;
    try {
      n = zmq::recv_multipart(impl_->socket, std::back_inserter(frames), zmq::recv_flags::dontwait);
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) {
        throw TransportError(impl_->endpoint,
                             fmt::format("receive: {} (errno {})", e.what(), e.num()));
      }
    }
    if (n && *n > 0) break;
  }
  Received r;
  r.peer = frames.front().to_string();
  if (frames.size() != 2) {
    // A DEALER sends exactly one frame per Envelope; a REQ-style empty delimiter or a multipart
    // message is not ours.
    r.error = fmt::format("a message of {} frames (a crashlink message is exactly one)",
                          frames.size() - 1);
    return r;
  }
  r.error = detail::parse(frames[1], r.envelope);
  if (r.ok()) {
    auto kept = std::make_unique<Payload::Impl>();
    kept->message = std::move(frames[1]);
    r.payload = Payload(std::move(kept));
  }
  return r;
}

}  // namespace crashlink::transport
