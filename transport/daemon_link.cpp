#include "transport/daemon_link.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>

#include "proto/envelope_name.h"
#include "transport/errors.h"

namespace crashlink::transport {

namespace {

const std::string kCoordinator = "coordinator";

}  // namespace

std::string session_routing_id(std::string_view domain) {
  std::random_device random;
  const std::uint64_t nonce = (static_cast<std::uint64_t>(random()) << 32) ^ random();
  return fmt::format("{}#{:016x}", domain.substr(0, 200), nonce);
}

DaemonLink::DaemonLink(std::string_view endpoint, const wire::Hello& hello,
                       const SessionOptions& options)
    : options_(options),
      domain_(hello.domain()),
      dealer_(endpoint, session_routing_id(hello.domain()), options.socket) {
  options_.validate(dealer_.endpoint());
  heartbeat_.mutable_heartbeat();
  wire::Envelope e;
  *e.mutable_hello() = hello;
  dealer_.send(e);
  const auto start = Clock::now();
  last_sent_ = start;
  const auto deadline = start + options_.handshake_timeout;
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      throw TransportError(
          dealer_.endpoint(),
          fmt::format("domain '{}': no answer to its Hello within {:.3f} s; is the coordinator "
                      "running and listening on this endpoint?",
                      hello.domain(),
                      static_cast<double>(options_.handshake_timeout.count()) * 1e-3));
    }
    if (options_.stop != nullptr && options_.stop->load())
      throw StopRequested(
          fmt::format("domain '{}': stopped on request while waiting for the "
                      "coordinator's answer to its Hello",
                      hello.domain()));
    auto r = dealer_.receive(std::min(left, std::chrono::milliseconds{100}));
    if (!r) continue;
    if (!r->ok()) {
      throw ProtocolError(kCoordinator,
                          fmt::format("the coordinator at {} answered the Hello of domain '{}' "
                                      "with {}",
                                      dealer_.endpoint(), hello.domain(), r->error));
    }
    if (r->envelope.has_error()) throw RemoteError(r->envelope.error());
    if (!r->envelope.has_hello() || r->envelope.hello().role() != wire::PEER_ROLE_COORDINATOR) {
      throw ProtocolError(
          kCoordinator,
          fmt::format("the coordinator at {} answered the Hello of domain '{}' "
                      "with a {} instead of a coordinator Hello",
                      dealer_.endpoint(), hello.domain(), wire::body_name(r->envelope)));
    }
    coordinator_hello_ = r->envelope.hello();
    break;
  }
  last_heard_ = Clock::now();
  open_ = true;
}

void DaemonLink::send(const wire::Envelope& envelope) {
  dealer_.send(envelope);
  last_sent_ = Clock::now();
  if (envelope.has_bye() || envelope.has_error()) open_ = false;
}

void DaemonLink::send_error(wire::ErrorCode code, std::string message) {
  (void)dealer_.try_send(make_error(code, std::move(message), domain()));
  last_sent_ = Clock::now();
  open_ = false;
}

void DaemonLink::bye(std::string reason) {
  send(make_bye(std::move(reason)));
}

std::optional<wire::Envelope> DaemonLink::receive(std::chrono::milliseconds timeout) {
  if (!inbox_.empty()) {
    auto e = std::move(inbox_.front());
    inbox_.pop_front();
    return e;
  }
  if (!open_) {
    throw ProtocolError(kCoordinator,
                        fmt::format("domain '{}': receive after the session with {} ended (Bye "
                                    "or Error)",
                                    domain(), endpoint()));
  }
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    auto now = Clock::now();
    send_heartbeat_if_idle(now);
    check_coordinator(now);
    if (!inbox_.empty()) return receive(timeout);
    // Wake up for the next heartbeat and for the peer timeout, whichever comes first.
    const auto until =
        std::min({deadline, last_sent_ + options_.heartbeat_interval,
                  last_heard_ + options_.peer_timeout + std::chrono::milliseconds{1}});
    const auto wait = std::max(std::chrono::ceil<std::chrono::milliseconds>(until - now),
                               std::chrono::milliseconds{0});
    if (auto r = dealer_.receive(wait)) {
      last_heard_ = Clock::now();
      if (auto e = accept(*r)) return e;
    }
    if (Clock::now() >= deadline) return std::nullopt;
  }
}

std::optional<wire::Envelope> DaemonLink::accept(Received& r) {
  if (!r.ok()) {
    throw ProtocolError(kCoordinator, fmt::format("the coordinator at {} sent domain '{}' {}",
                                                  endpoint(), domain(), r.error));
  }
  switch (r.envelope.body_case()) {
    case wire::Envelope::kHeartbeat:
      return std::nullopt;
    case wire::Envelope::kError:
      open_ = false;
      throw RemoteError(r.envelope.error());
    case wire::Envelope::kHello:
      throw ProtocolError(kCoordinator,
                          fmt::format("the coordinator at {} sent domain '{}' a second Hello "
                                      "in the middle of the session",
                                      endpoint(), domain()));
    case wire::Envelope::kBye:
      open_ = false;
      return std::move(r.envelope);
    default:
      return std::move(r.envelope);
  }
}

void DaemonLink::keep_alive() {
  const auto now = Clock::now();
  send_heartbeat_if_idle(now);
  check_coordinator(now);
}

void DaemonLink::check_coordinator(Clock::time_point now) {
  if (now - last_heard_ <= options_.peer_timeout) return;
  // What came while this process was not running counts: read it before judging.
  while (open_) {
    auto r = dealer_.receive(std::chrono::milliseconds{0});
    if (!r) break;
    last_heard_ = Clock::now();
    if (auto e = accept(*r)) inbox_.push_back(std::move(*e));
  }
  now = Clock::now();
  if (now - last_heard_ > options_.peer_timeout) {
    throw PeerTimeoutError(
        endpoint(), kCoordinator,
        fmt::format("the coordinator at {} (seen by domain '{}')", endpoint(), domain()),
        std::chrono::duration_cast<std::chrono::milliseconds>(now - last_heard_),
        options_.peer_timeout);
  }
}

void DaemonLink::send_heartbeat_if_idle(Clock::time_point now) {
  if (!open_ || now - last_sent_ < options_.heartbeat_interval) return;
  heartbeat_.mutable_heartbeat()->set_sequence(++heartbeat_sequence_);
  (void)dealer_.try_send(heartbeat_);  // never wait: if it cannot queue, the timeout will tell
  last_sent_ = now;
}

}  // namespace crashlink::transport
