#include "transport/dealer.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "transport/curve_errors.h"
#include "transport/curve_policy.h"
#include "transport/curve_support.h"
#include "transport/detail/handshake_monitor.h"
#include "transport/detail/zmq.h"
#include "transport/endpoint.h"
#include "transport/errors.h"

namespace crashlink::transport {

namespace {

/// Handshakes the coordinator closed in a row, with no detail, before a CURVE daemon concludes
/// that the coordinator cannot decrypt its HELLO (a wrong server key): one can be a coordinator
/// restarting; ZeroMQ reconnects every 100 ms, so three take about 0.3 s.
constexpr int kClosedHandshakesToRefuse = 3;

}  // namespace

struct Dealer::Impl {
  zmq::socket_t socket;
  std::string endpoint;
  std::string routing_id;
  std::string name;  // for messages: the routing id up to its first '#' (the domain)
  zmq::message_t message;
  std::optional<CurveClientKeys> curve;
  // tcp and ipc: handshake events, so that a refusal is reported at once (check_handshake()).
  std::optional<detail::HandshakeMonitor> monitor;
  int closed_handshakes = 0;

  /// Throws CurveRefusedError if the monitor saw the coordinator refuse the security handshake.
  void check_handshake();
  /// Waits until the socket or the monitor has something, or `timeout`.
  void wait(std::chrono::milliseconds timeout);
  [[noreturn]] void refused(const std::string& why) const;

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
  impl_->name = printable_peer(routing_id.substr(0, routing_id.find('#')));
  try {
    impl_->socket = zmq::socket_t(detail::process_context(), zmq::socket_type::dealer);
    detail::configure(impl_->socket, options);
    impl_->socket.set(zmq::sockopt::routing_id, zmq::buffer(routing_id.data(), routing_id.size()));
    impl_->curve = curve_client_keys(parsed, options.curve);
    if (impl_->curve) {
      require_curve(fmt::format("domain '{}' connecting to {}", impl_->name, parsed.text));
      impl_->socket.set(zmq::sockopt::curve_serverkey, impl_->curve->server_key);
      impl_->socket.set(zmq::sockopt::curve_publickey, impl_->curve->public_key);
      impl_->socket.set(zmq::sockopt::curve_secretkey, impl_->curve->secret_key);
    }
    if (parsed.scheme != Scheme::inproc) impl_->monitor.emplace(impl_->socket);
    impl_->socket.connect(parsed.text);
  } catch (const zmq::error_t& e) {
    throw TransportError(parsed.text,
                         fmt::format("cannot connect: {} (errno {})", e.what(), e.num()));
  }
}

void Dealer::Impl::refused(const std::string& why) const {
  throw CurveRefusedError(endpoint, fmt::format("the coordinator refused the connection of domain "
                                                "'{}': {}",
                                                name, why));
}

void Dealer::Impl::check_handshake() {
  if (!monitor) return;
  for (const auto& e : monitor->drain()) {
    switch (e.event) {
      case ZMQ_EVENT_HANDSHAKE_SUCCEEDED:
        closed_handshakes = 0;
        break;
      case ZMQ_EVENT_HANDSHAKE_FAILED_AUTH:
        refused(fmt::format(
            "it refused this daemon's CURVE key (ZAP status {}): public key {} is not in the "
            "coordinator's authorized keys file; fix: append this daemon's PREFIX.pub (the key "
            "{}) to the file the coordinator was started with (--curve-authorized-keys) and "
            "restart the coordinator, or start this daemon with a --curve-secret-key whose "
            "public key is in that file",
            e.value, curve ? curve->public_key : std::string("(none)"),
            curve ? curve->public_key : std::string("(none)")));
      case ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL:
        if (e.value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) {
          refused(
              curve ? fmt::format("this daemon uses CURVE and the coordinator does not ({}); fix: "
                                  "start the coordinator with --curve and its keys too, or both "
                                  "without CURVE on a loopback or ipc endpoint",
                                  detail::protocol_error_name(e.value))
                    : fmt::format("the coordinator requires CURVE and this daemon does not use it "
                                  "({}); fix: start this daemon with --curve, --curve-secret-key "
                                  "FILE and --curve-server-key FILE (the coordinator's PREFIX.pub)",
                                  detail::protocol_error_name(e.value)));
        }
        if (!curve) break;
        if (e.value == ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC) {
          refused(fmt::format(
              "the CURVE handshake failed its cryptographic check ({}): the server public key "
              "given to this daemon ({}) is not the coordinator's; fix: pass the coordinator's "
              "PREFIX.pub as --curve-server-key",
              detail::protocol_error_name(e.value), curve->server_key));
        }
        refused(fmt::format("the CURVE handshake failed with {}",
                            detail::protocol_error_name(e.value)));
      case ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL:
        if (!curve) break;
        if (++closed_handshakes >= kClosedHandshakesToRefuse) {
          refused(fmt::format(
              "it closed the connection during the CURVE handshake {} times in a row: it cannot "
              "decrypt this daemon's HELLO, so the server public key given to this daemon ({}) "
              "is not the coordinator's; fix: pass the coordinator's PREFIX.pub as "
              "--curve-server-key",
              closed_handshakes, curve->server_key));
        }
        break;
      default:
        break;
    }
  }
}

void Dealer::Impl::wait(std::chrono::milliseconds timeout) {
  if (!monitor) {
    detail::wait_readable(socket, timeout);
    return;
  }
  zmq::pollitem_t items[] = {{socket.handle(), 0, ZMQ_POLLIN, 0},
                             {monitor->socket().handle(), 0, ZMQ_POLLIN, 0}};
  try {
    (void)zmq::poll(items, 2, std::max(timeout, std::chrono::milliseconds{0}));
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;
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
bool Dealer::curve() const {
  return impl_->curve.has_value();
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
    impl_->check_handshake();
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
    impl_->wait(left);
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
