// Process-wide context and the codec shared by Router and Dealer (detail/zmq.h).
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <utility>

#include "core/log_escape.h"
#include "transport/detail/zmq.h"
#include "transport/received.h"

namespace crashlink::transport {

namespace detail {

zmq::context_t& process_context() {
  // A function-local static: constructed before the first socket, so destroyed after the last
  // static one; its destructor (zmq_ctx_term) waits for linger on unsent messages at exit.
  static zmq::context_t context(1);
  return context;
}

void configure(zmq::socket_t& socket, const SocketOptions& options) {
  socket.set(zmq::sockopt::linger, options.linger_ms);
  socket.set(zmq::sockopt::sndhwm, options.send_hwm);
  socket.set(zmq::sockopt::rcvhwm, options.receive_hwm);
  socket.set(zmq::sockopt::sndtimeo, options.send_timeout_ms);
  socket.set(zmq::sockopt::maxmsgsize, options.max_message_bytes);
}

zmq::message_t serialize(const wire::Envelope& envelope) {
  const std::size_t size = envelope.ByteSizeLong();
  zmq::message_t message(size);
  if (size > 0 &&
      !envelope.SerializeWithCachedSizesToArray(static_cast<std::uint8_t*>(message.data()))) {
    throw std::logic_error("crashlink::transport: Envelope serialization failed");
  }
  return message;
}

std::string parse(const zmq::message_t& message, wire::Envelope& envelope) {
  envelope.Clear();
  const std::size_t size = message.size();
  const auto* bytes = static_cast<const unsigned char*>(message.data());
  std::string head;
  for (std::size_t i = 0; i < std::min<std::size_t>(size, 8); ++i) {
    head += fmt::format("{:02x}", bytes[i]);
  }
  if (size > static_cast<std::size_t>(INT_MAX)) {
    return fmt::format("{} bytes, larger than a protobuf message can be", size);
  }
  if (!envelope.ParseFromArray(message.data(), static_cast<int>(size))) {
    envelope.Clear();
    return fmt::format("{} bytes (starting {}) that do not parse as a crashlink.wire.Envelope",
                       size, head);
  }
  if (envelope.body_case() == wire::Envelope::BODY_NOT_SET) {
    envelope.Clear();
    return fmt::format("{} bytes (starting {}) that parse as an Envelope with no message in it",
                       size, head);
  }
  return {};
}

bool wait_readable(zmq::socket_t& socket, std::chrono::milliseconds timeout) {
  zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
  try {
    return zmq::poll(&item, 1, std::max(timeout, std::chrono::milliseconds{0})) > 0;
  } catch (const zmq::error_t& e) {
    if (e.num() == EINTR) return false;
    throw;
  }
}

}  // namespace detail

Payload::Payload() = default;
Payload::~Payload() = default;
Payload::Payload(Payload&&) noexcept = default;
Payload& Payload::operator=(Payload&&) noexcept = default;
Payload::Payload(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

std::size_t Payload::size() const {
  return impl_ ? impl_->message.size() : 0;
}

std::string printable_peer(std::string_view routing_id) {
  return core::log_escape(routing_id);
}

}  // namespace crashlink::transport
