#include "transport/coordinator_link.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>

#include "proto/protocol_version.h"
#include "transport/errors.h"

namespace crashlink::transport {

namespace {

constexpr std::size_t kMaxNotices = 1000;

std::chrono::milliseconds since(std::chrono::steady_clock::time_point then,
                                std::chrono::steady_clock::time_point now) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(now - then);
}

}  // namespace

CoordinatorLink::CoordinatorLink(std::string_view endpoint, CoordinatorConfig config)
    : config_(std::move(config)), router_(endpoint, config_.options.socket) {
  config_.options.validate(router_.endpoint());
  heartbeat_.mutable_heartbeat();
}

std::optional<Incoming> CoordinatorLink::poll(std::chrono::milliseconds timeout) {
  if (!queued_.empty()) {
    Incoming in = std::move(queued_.front());
    queued_.pop_front();
    return in;
  }
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    auto now = Clock::now();
    send_heartbeats(now);
    const auto until = std::min(deadline, next_heartbeat());
    const auto wait = std::max(std::chrono::ceil<std::chrono::milliseconds>(until - now),
                               std::chrono::milliseconds{0});
    auto received = router_.receive(wait);
    collect_refusals();
    if (received) {
      const auto joins_before = joins_;
      if (auto in = handle(*received, Clock::now())) return in;
      if (joins_ != joins_before) return std::nullopt;  // a domain joined: an event too
    }
    if (Clock::now() >= deadline) return std::nullopt;
  }
}

std::optional<Incoming> CoordinatorLink::handle(Received& received, Clock::time_point now) {
  const std::string& id = received.peer;
  const auto d = domain_of_.find(id);
  Peer* peer = d == domain_of_.end() ? nullptr : &peers_.at(d->second);
  if (peer != nullptr && peer->active) peer->last_heard = now;  // any message at all counts
  if (!received.ok()) {
    const std::string text =
        fmt::format("peer '{}' sent {}; refused", printable_peer(id), received.error);
    notice(id, text);
    reply_error(id, wire::ERROR_CODE_PROTOCOL, text);
    return std::nullopt;
  }
  wire::Envelope& envelope = received.envelope;
  if (envelope.has_hello()) {
    if (peer != nullptr && peer->active) {
      const std::string text = fmt::format(
          "domain '{}' sent a second Hello in the middle of its session; refused", d->second);
      notice(id, text);
      reply_error(id, wire::ERROR_CODE_PROTOCOL, text);
      return std::nullopt;
    }
    handshake(id, envelope.hello(), now);
    return std::nullopt;
  }
  if (peer == nullptr || !peer->active) {
    const char* what = peer == nullptr ? "before its Hello" : "after the end of its session";
    const auto* field = wire::Envelope::descriptor()->FindFieldByNumber(envelope.body_case());
    const std::string text =
        fmt::format("peer '{}' sent a {} {}; dropped (every connection starts with a Hello)",
                    printable_peer(id), field != nullptr ? field->name() : "empty Envelope", what);
    notice(id, text);
    if (peer == nullptr) reply_error(id, wire::ERROR_CODE_PROTOCOL, text);
    return std::nullopt;
  }
  switch (envelope.body_case()) {
    case wire::Envelope::kHeartbeat:
      return std::nullopt;
    case wire::Envelope::kError:
      // The daemon's own name for itself is a string from the network: the session's domain is
      // the one its Hello was accepted for.
      envelope.mutable_error()->set_domain(d->second);
      peer->active = false;
      break;
    case wire::Envelope::kBye:
      peer->active = false;
      break;
    default:
      break;
  }
  return Incoming{d->second, std::move(envelope), std::move(received.payload)};
}

void CoordinatorLink::handshake(const std::string& routing_id, const wire::Hello& hello,
                                Clock::time_point now) {
  auto refusal = check_hello(hello, config_.scenario_hash, config_.domains);
  if (!refusal) refusal = check_free(hello.domain(), now);
  if (refusal) {
    notice(routing_id, fmt::format("refused Hello from '{}': {}", printable_peer(routing_id),
                                   refusal->message()));
    wire::Envelope e;
    *e.mutable_error() = std::move(*refusal);
    try {
      router_.send(routing_id, e);
    } catch (const TransportError& x) {
      notice(routing_id, x.what());
    }
    return;
  }
  wire::Envelope reply;
  auto* h = reply.mutable_hello();
  h->set_protocol_version(wire::kProtocolVersion);
  h->set_scenario_hash(config_.scenario_hash);
  h->set_role(wire::PEER_ROLE_COORDINATOR);
  h->set_ticks_per_second(config_.ticks_per_second);
  router_.send(routing_id, reply);
  Peer& peer = peers_[hello.domain()];
  if (!peer.routing_id.empty()) domain_of_.erase(peer.routing_id);  // its earlier session's
  peer = Peer{routing_id, now, now, now, true};
  domain_of_[routing_id] = hello.domain();
  ++joins_;
}

std::optional<wire::Error> CoordinatorLink::check_free(const std::string& domain,
                                                       Clock::time_point now) const {
  auto held = [&](std::string text) {
    wire::Error e;
    e.set_code(wire::ERROR_CODE_DOMAIN_HELD);
    e.set_message(std::move(text));
    e.set_domain(domain);
    return std::optional<wire::Error>(std::move(e));
  };
  const auto it = peers_.find(domain);
  if (it != peers_.end() && it->second.active) {
    return held(fmt::format(
        "domain '{}' is already held by a daemon in this run (connection '{}', joined {:.1f} s "
        "ago, last heard {:.1f} s ago); a domain has one daemon: this one is refused and the "
        "running one goes on; fix: stop this daemon, or start it with another --domain (the "
        "scenario's domains are '{}')",
        domain, printable_peer(it->second.routing_id),
        static_cast<double>(since(it->second.joined, now).count()) * 1e-3,
        static_cast<double>(since(it->second.last_heard, now).count()) * 1e-3,
        fmt::join(config_.domains, "', '")));
  }
  if (const auto s = sealed_.find(domain); s != sealed_.end()) {
    return held(fmt::format(
        "domain '{}' has already run in this run (its daemon registered {:.1f} s ago and its "
        "session has ended); a domain has one daemon per run: this one is refused; fix: start a "
        "new run (a new coordinator) for another attempt",
        domain, static_cast<double>(since(s->second, now).count()) * 1e-3));
  }
  return std::nullopt;
}

void CoordinatorLink::seal(std::string_view domain) {
  sealed_.try_emplace(std::string(domain), Clock::now());
}

void CoordinatorLink::drop(std::string_view domain, wire::ErrorCode code, const std::string& text) {
  const auto it = peers_.find(std::string(domain));
  if (it == peers_.end() || !it->second.active) return;
  const std::string id = it->second.routing_id;
  notice(id, text);
  try {
    router_.send(id, make_error(code, text, std::string(domain)));
  } catch (const TransportError& x) {
    notice(id, x.what());  // gone already
  }
  domain_of_.erase(id);
  peers_.erase(it);  // missing() again: a new daemon may join (unless sealed)
}

void CoordinatorLink::reply_error(const std::string& routing_id, wire::ErrorCode code,
                                  const std::string& text) {
  try {
    router_.send(routing_id, make_error(code, text, printable_peer(routing_id)));
  } catch (const TransportError& x) {
    notice(routing_id, x.what());  // the garbage sender is gone already
  }
}

void CoordinatorLink::send(std::string_view domain, const wire::Envelope& envelope) {
  const auto it = peers_.find(std::string(domain));
  if (it == peers_.end() || !it->second.active) {
    throw TransportError(endpoint(),
                         fmt::format("send to domain '{}': it has not joined or its session has "
                                     "ended (Bye or Error)",
                                     domain));
  }
  router_.send(it->second.routing_id, envelope);
  it->second.last_sent = Clock::now();
  if (envelope.has_bye() || envelope.has_error()) it->second.active = false;
}

void CoordinatorLink::forward(std::string_view domain, Incoming& message) {
  if (message.payload.empty()) {
    send(domain, message.envelope);
    return;
  }
  const auto it = peers_.find(std::string(domain));
  if (it == peers_.end() || !it->second.active) {
    throw TransportError(endpoint(),
                         fmt::format("forward to domain '{}': it has not joined or its session "
                                     "has ended (Bye or Error)",
                                     domain));
  }
  if (message.envelope.has_bye() || message.envelope.has_error()) {
    send(domain, message.envelope);  // ends that session: keep send()'s bookkeeping
    return;
  }
  router_.forward(it->second.routing_id, std::move(message.payload));
  it->second.last_sent = Clock::now();
}

bool CoordinatorLink::joined(std::string_view domain) const {
  const auto it = peers_.find(std::string(domain));
  return it != peers_.end() && it->second.active;
}

bool CoordinatorLink::all_joined() const {
  return missing().empty();
}

std::vector<std::string> CoordinatorLink::missing() const {
  std::vector<std::string> out;
  for (const auto& d : config_.domains) {
    if (!peers_.contains(d)) out.push_back(d);
  }
  return out;
}

void CoordinatorLink::await_all_joined(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (!all_joined()) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      throw TransportError(
          endpoint(),
          fmt::format("domains '{}' did not join within {:.3f} s (no accepted Hello); "
                      "are their daemons started and connected to this endpoint?",
                      fmt::join(missing(), "', '"), static_cast<double>(timeout.count()) * 1e-3));
    }
    // Messages of domains that joined already are kept in order for poll().
    auto queued = std::move(queued_);
    queued_.clear();
    auto in = poll(left);
    queued_ = std::move(queued);
    if (in) queued_.push_back(std::move(*in));
  }
}

std::vector<std::string> CoordinatorLink::dead_peers() const {
  const auto now = Clock::now();
  std::vector<std::string> out;
  for (const auto& d : config_.domains) {
    const auto it = peers_.find(d);
    if (it != peers_.end() && it->second.active &&
        now - it->second.last_heard >
            std::max(config_.options.peer_timeout, it->second.allowed_silence)) {
      out.push_back(d);
    }
  }
  return out;
}

void CoordinatorLink::allow_silence(std::string_view domain, std::chrono::milliseconds timeout) {
  const auto it = peers_.find(std::string(domain));
  if (it != peers_.end()) it->second.allowed_silence = timeout;
}

void CoordinatorLink::check_alive() {
  if (dead_peers().empty()) return;
  while (auto received = router_.receive(std::chrono::milliseconds{0})) {
    collect_refusals();
    if (auto in = handle(*received, Clock::now())) queued_.push_back(std::move(*in));
  }
  const auto dead = dead_peers();
  if (dead.empty()) return;
  const auto silent = since(peers_.at(dead.front()).last_heard, Clock::now());
  const std::string description =
      fmt::format("{} '{}'", dead.size() == 1 ? "domain" : "domains", fmt::join(dead, "', '"));
  throw PeerTimeoutError(
      endpoint(), dead.front(), description, silent,
      std::max(config_.options.peer_timeout, peers_.at(dead.front()).allowed_silence));
}

std::vector<Notice> CoordinatorLink::take_notices() {
  return std::exchange(notices_, {});
}

void CoordinatorLink::send_heartbeats(Clock::time_point now) {
  for (auto& [domain, peer] : peers_) {
    if (!peer.active || now - peer.last_sent < config_.options.heartbeat_interval) continue;
    heartbeat_.mutable_heartbeat()->set_sequence(++heartbeat_sequence_);
    peer.last_sent = now;
    try {
      // Never wait: a full queue means the peer is not reading; the timeout will tell.
      (void)router_.try_send(peer.routing_id, heartbeat_);
    } catch (const TransportError& x) {
      // Disconnected: the peer timeout will name it; keep serving the others.
      notice(peer.routing_id, fmt::format("heartbeat to domain '{}' failed: {}", domain, x.what()));
    }
  }
}

CoordinatorLink::Clock::time_point CoordinatorLink::next_heartbeat() const {
  auto next = Clock::time_point::max();
  for (const auto& [id, peer] : peers_) {
    if (peer.active) next = std::min(next, peer.last_sent + config_.options.heartbeat_interval);
  }
  return next;
}

void CoordinatorLink::collect_refusals() {
  if (!router_.curve()) return;
  for (auto& r : router_.take_refusals()) {
    notice(r.client_key.empty() ? r.address : r.client_key, std::move(r.text));
  }
}

void CoordinatorLink::notice(const std::string& routing_id, std::string text) {
  if (notices_.size() >= kMaxNotices) {
    ++dropped_notices_;
    return;
  }
  notices_.push_back(Notice{printable_peer(routing_id), std::move(text)});
}

}  // namespace crashlink::transport
