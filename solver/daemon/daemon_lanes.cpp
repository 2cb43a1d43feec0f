#include "solver/daemon/daemon_lanes.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <thread>
#include <utility>

#include "core/errors.h"
#include "core/log_escape.h"
#include "proto/envelope_name.h"
#include "transport/errors.h"
#include "transport/lane_endpoint.h"

namespace crashlink::daemon {

void DaemonLanes::open_own(const std::string& coordinator_endpoint) {
  const auto lane =
      transport::lane_endpoint_for(coordinator_endpoint, domain_, session_.socket.curve);
  try {
    if (lane.rfind(transport::kShmScheme, 0) == 0) {
      shm_in_ = std::make_unique<transport::ShmLaneIn>(lane.substr(transport::kShmScheme.size()));
      endpoint_ = shm_in_->endpoint();
    } else if (!lane.empty()) {
      // Across hosts a CURVE server with this daemon's own key; the partners' keys come with the
      // Setup (Router::authorize), a partner connecting earlier waits for them.
      auto options = session_.socket;
      options.curve.authorize_later = true;
      zmq_in_ = std::make_unique<transport::Router>(lane, options);
      endpoint_ = zmq_in_->endpoint();
    }
  } catch (const transport::TransportError& e) {
    std::fprintf(stderr,
                 "crashlink-solver: domain '%s': no lane (%s); the coordinator routes this "
                 "domain's vectors\n",
                 domain_.c_str(), e.what());
    shm_in_.reset();
    zmq_in_.reset();
    endpoint_.clear();
  }
}

std::string DaemonLanes::public_key() const {
  return zmq_in_ ? zmq_in_->curve_public_key() : std::string();
}

std::int64_t injected_lane_delay_ms(const std::string& domain) {
  const char* v = std::getenv("CRASHLINK_INJECT_LANE_DELAY");
  if (v == nullptr) return 0;
  const std::string s(v);
  const auto colon = s.rfind(':');
  std::int64_t ms = -1;
  if (colon != std::string::npos) {
    const char* first = s.data() + colon + 1;
    const char* last = s.data() + s.size();
    const auto [end, ec] = std::from_chars(first, last, ms);
    if (ec != std::errc() || end != last || first == last) ms = -1;
  }
  if (ms < 0)
    throw InputError(
        fmt::format("CRASHLINK_INJECT_LANE_DELAY='{}': expected DOMAIN:MILLISECONDS "
                    "(an integer >= 0)",
                    core::log_escape(s)));
  return s.substr(0, colon) == domain ? ms : 0;
}

void DaemonLanes::connect(const wire::Setup& setup,
                          const std::vector<coupling::LanePartner>& partners,
                          const std::function<void()>& keep_alive) {
  if (setup.lanes_size() == 0) return;
  if (endpoint_.empty()) {
    throw ProtocolError("coordinator",
                        fmt::format("the Setup of domain '{}' lists {} lanes, but this daemon "
                                    "offered none",
                                    domain_, setup.lanes_size()));
  }
  std::vector<std::string> partner_keys;  // the clients our CURVE lane accepts
  for (const auto& lane : setup.lanes()) {
    Out out;
    if (lane.endpoint().rfind(transport::kShmScheme, 0) == 0) {
      if (!shm_in_) {
        throw ProtocolError(
            "coordinator",
            fmt::format("the Setup of domain '{}' gives '{}' the shared-memory "
                        "lane {}, but this daemon's lane is {}",
                        domain_, core::log_escape(lane.domain()),
                        core::log_escape(lane.endpoint(), core::kLogTextBytes), endpoint_));
      }
      // Its vectors to us, created before it can send: room for 8 of the largest (two 3-vectors
      // of doubles per J node, plus the envelope).
      std::size_t largest = 0;
      for (const auto& p : partners)
        if (p.partner == lane.domain()) largest = std::max(largest, p.j_nodes);
      shm_in_->add_partner(lane.domain(), 8 * (48 * largest + 1024));
      out.shm =
          std::make_unique<transport::ShmLaneOut>(lane.endpoint(), domain_, session_.peer_timeout);
    } else {
      auto options = session_.socket;
      options.curve.server_key = lane.public_key();  // used when CURVE is on for that endpoint
      out.zmq = std::make_unique<transport::Dealer>(lane.endpoint(), domain_, options);
      partner_keys.push_back(lane.public_key());
    }
    out_.emplace(lane.domain(), std::move(out));
  }
  if (zmq_in_) zmq_in_->authorize(std::move(partner_keys));
  // Every partner's ring is opened now, while the partner is sure to be there: it keeps its files
  // until every sender has opened them (hold_until_opened), but only until then. A sender that
  // opened at its first vector found, after a restart a step before the end, a partner that had
  // ended and taken its files with it (the first send after the restart was the last one).
  if (const auto ms = injected_lane_delay_ms(domain_); ms > 0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds{ms};
    while (std::chrono::steady_clock::now() < until) {
      keep_alive();
      std::this_thread::sleep_for(std::chrono::milliseconds{10});
    }
  }
  for (auto& [partner, out] : out_)
    if (out.shm) out.shm->open(keep_alive);
  for (const auto& p : partners) {
    const auto it = out_.find(p.partner);
    if (it == out_.end()) {
      throw ProtocolError("coordinator",
                          fmt::format("the Setup of domain '{}' has no lane to '{}', its "
                                      "partner on interface {}",
                                      domain_, p.partner, p.interface_index));
    }
    if (of_interface_.size() <= p.interface_index)
      of_interface_.resize(p.interface_index + 1, nullptr);
    of_interface_[p.interface_index] = &it->second;
  }
}

bool DaemonLanes::hold_until_opened(std::chrono::milliseconds timeout,
                                    const std::function<bool()>& go_on) const {
  if (!shm_in_) return true;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!shm_in_->all_opened()) {
    if (std::chrono::steady_clock::now() >= deadline || !go_on()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds{1});
  }
  return true;
}

bool DaemonLanes::send(std::int64_t interface_index, const wire::Envelope& e) {
  const auto i = static_cast<std::size_t>(interface_index);
  if (interface_index < 0 || i >= of_interface_.size() || of_interface_[i] == nullptr) return false;
  Out& out = *of_interface_[i];
  if (out.zmq) {
    out.zmq->send(e);
  } else {
    out.shm->send_message(e);
  }
  return true;
}

std::optional<wire::Envelope> DaemonLanes::receive(std::chrono::milliseconds wait,
                                                   const coupling::DomainScheme& scheme) {
  std::string peer, what;
  wire::Envelope e;
  bool ok = false;
  if (shm_in_) {
    if (!shm_in_->receive_into(wait, peer, bytes_)) return std::nullopt;
    ok = e.ParseFromString(bytes_);
    if (!ok) what = fmt::format("{} bytes that are not an Envelope", bytes_.size());
  } else {
    auto r = zmq_in_->receive(wait);
    if (!r) return std::nullopt;
    peer = r->peer;
    ok = r->ok();
    what = ok ? std::string() : r->error;
    if (ok) e = std::move(r->envelope);
  }
  if (!ok || out_.find(peer) == out_.end() || !scheme.lane_message(e)) {
    throw ProtocolError("lane",
                        fmt::format("domain '{}' got {} on its lane {} from '{}'; a lane carries "
                                    "only its partners' vectors",
                                    domain_, ok ? wire::body_name(e) : what, endpoint_,
                                    transport::printable_peer(peer)));
  }
  return e;
}

}  // namespace crashlink::daemon
