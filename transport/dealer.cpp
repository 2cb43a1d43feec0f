#include "transport/dealer.h"

#include <fmt/format.h>

#include "transport/detail/zmq.h"
#include "transport/endpoint.h"
#include "transport/errors.h"

namespace crashlink::transport {

struct Dealer::Impl {
  zmq::socket_t socket;
  std::string endpoint;
  std::string routing_id;
  zmq::message_t message;

  bool send(zmq::message_t& payload, zmq::send_flags wait) {
    try {
      return socket.send(payload, wait).has_value();
    } catch (const zmq::error_t& e) {
      throw TransportError(endpoint, fmt::format("send: {} (errno {})", e.what(), e.num()));
    }
  }
};

Dealer::Dealer(std::string_view endpoint, std::string_view routing_id, const SocketOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const Endpoint parsed = parse_endpoint(endpoint, Use::connect);
  if (routing_id.empty() || routing_id.size() > 255 || routing_id.front() == '\0') {
    throw TransportError(parsed.text,
                         fmt::format("routing id '{}' ({} bytes) must be 1-255 bytes and not "
                                     "start with a zero byte; it is the domain name: rename the "
                                     "domain in the scenario",
                                     printable_peer(routing_id), routing_id.size()));
  }
  impl_->endpoint = parsed.text;
  impl_->routing_id = std::string(routing_id);
  try {
    impl_->socket = zmq::socket_t(detail::process_context(), zmq::socket_type::dealer);
    detail::configure(impl_->socket, options);
    impl_->socket.set(zmq::sockopt::routing_id, zmq::buffer(routing_id.data(), routing_id.size()));
    impl_->socket.connect(parsed.text);
  } catch (const zmq::error_t& e) {
    throw TransportError(parsed.text,
                         fmt::format("cannot connect: {} (errno {})", e.what(), e.num()));
  }
}

Dealer::~Dealer() = default;
Dealer::Dealer(Dealer&&) noexcept = default;
Dealer& Dealer::operator=(Dealer&&) noexcept = default;

const std::string& Dealer::endpoint() const {
  return impl_->endpoint;
}
const std::string& Dealer::routing_id() const {
  return impl_->routing_id;
}

namespace {

[[noreturn]] void send_timed_out(const std::string& endpoint) {
  throw TransportError(endpoint,
                       "send timed out: the queue to the coordinator is full "
                       "(coordinator stalled or unreachable)");
}

}  // namespace

void Dealer::send(const wire::Envelope& envelope) {
  zmq::message_t payload = detail::serialize(envelope);
  if (!impl_->send(payload, zmq::send_flags::none)) send_timed_out(impl_->endpoint);
}

bool Dealer::try_send(const wire::Envelope& envelope) {
  zmq::message_t payload = detail::serialize(envelope);
  return impl_->send(payload, zmq::send_flags::dontwait);
}

void Dealer::send_raw(std::string_view bytes) {
  zmq::message_t payload(bytes.data(), bytes.size());
  if (!impl_->send(payload, zmq::send_flags::none)) send_timed_out(impl_->endpoint);
}

std::optional<Received> Dealer::receive(std::chrono::milliseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + timeout;
  auto& message = impl_->message;
  for (;;) {
    zmq::recv_result_t n;
    try {
      n = impl_->socket.recv(message, zmq::recv_flags::dontwait);
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) {
        throw TransportError(impl_->endpoint,
                             fmt::format("receive: {} (errno {})", e.what(), e.num()));
      }
    }
    if (n) break;
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    detail::wait_readable(impl_->socket, left);
  }
  Received r;
  if (message.more()) {
    // Drain the rest of a multipart message: a crashlink message is one frame.
    std::size_t frames = 1;
    while (message.more()) {
      (void)impl_->socket.recv(message, zmq::recv_flags::none);
      ++frames;
    }
    r.error = fmt::format("a message of {} frames (a crashlink message is exactly one)", frames);
    return r;
  }
  r.error = detail::parse(message, r.envelope);
  return r;
}

}  // namespace crashlink::transport
