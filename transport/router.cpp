#include "transport/router.h"

#include <fmt/format.h>

#include <iterator>
#include <vector>

#include "transport/detail/zmq.h"
#include "transport/endpoint.h"
#include "transport/errors.h"

namespace crashlink::transport {

struct Router::Impl {
  zmq::socket_t socket;
  std::string endpoint;
  std::vector<zmq::message_t> frames;

  /// False when the first frame cannot be queued (EAGAIN: queue full, after the send timeout if
  /// `wait` is none); throws TransportError for an unknown peer.
  bool send(std::string_view peer, const wire::Envelope& envelope, zmq::send_flags wait);
};

Router::Router(std::string_view endpoint, const SocketOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const Endpoint parsed = parse_endpoint(endpoint, Use::bind);
  try {
    impl_->socket = zmq::socket_t(detail::process_context(), zmq::socket_type::router);
    detail::configure(impl_->socket, options);
    impl_->socket.set(zmq::sockopt::router_mandatory, true);
    impl_->socket.bind(parsed.text);
    impl_->endpoint = impl_->socket.get(zmq::sockopt::last_endpoint);
  } catch (const zmq::error_t& e) {
    throw TransportError(parsed.text, fmt::format("cannot bind: {} (errno {}); is the endpoint "
                                                  "in use by another run or not a local address?",
                                                  e.what(), e.num()));
  }
}

Router::~Router() = default;
Router::Router(Router&&) noexcept = default;
Router& Router::operator=(Router&&) noexcept = default;

const std::string& Router::endpoint() const {
  return impl_->endpoint;
}

void Router::send(std::string_view peer, const wire::Envelope& envelope) {
  if (!impl_->send(peer, envelope, zmq::send_flags::none)) {
    throw TransportError(impl_->endpoint,
                         fmt::format("send to '{}' timed out: its queue is full (peer stalled "
                                     "or gone)",
                                     printable_peer(peer)));
  }
}

bool Router::try_send(std::string_view peer, const wire::Envelope& envelope) {
  return impl_->send(peer, envelope, zmq::send_flags::dontwait);
}

bool Router::Impl::send(std::string_view peer, const wire::Envelope& envelope,
                        zmq::send_flags wait) {
  zmq::message_t payload = detail::serialize(envelope);
  try {
    // ROUTER_MANDATORY fails the first frame for an unknown peer (EHOSTUNREACH) or a full queue
    // (EAGAIN), so nothing half-sent remains; the second frame then always queues.
    if (!socket.send(zmq::buffer(peer.data(), peer.size()), zmq::send_flags::sndmore | wait)) {
      return false;
    }
    (void)socket.send(payload, zmq::send_flags::none);
    return true;
  } catch (const zmq::error_t& e) {
    if (e.num() == EHOSTUNREACH) {
      throw TransportError(endpoint,
                           fmt::format("send to '{}': no such peer connected (it never connected "
                                       "or has disconnected)",
                                       printable_peer(peer)));
    }
    throw TransportError(endpoint, fmt::format("send to '{}': {} (errno {})", printable_peer(peer),
                                               e.what(), e.num()));
  }
}

std::optional<Received> Router::receive(std::chrono::milliseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + timeout;
  auto& frames = impl_->frames;
  for (;;) {
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
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    detail::wait_readable(impl_->socket, left);
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
  return r;
}

}  // namespace crashlink::transport
