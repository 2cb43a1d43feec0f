#include "coordinator/admission.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "coordinator/coordinator_stops.h"
#include "core/errors.h"
#include "core/exit_codes.h"
#include "proto/envelope_name.h"

namespace crashlink::coordinator {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

Admission::Admission(const CoordinatorOptions& o, const CoordinatorScheme& scheme,
                     transport::CoordinatorLink& link)
    : o_(o),
      scheme_(scheme),
      link_(link),
      regs_(scheme.cut().names.size()),
      registered_(scheme.cut().names.size(), false) {}

int Admission::index_of(const std::string& domain) const {
  const auto& names = scheme_.cut().names;
  const auto it = std::find(names.begin(), names.end(), domain);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

std::vector<std::string> Admission::lane_endpoints() const {
  std::vector<std::string> lanes;
  for (std::size_t k = 0; k < regs_.size(); ++k)
    if (registered_[k]) lanes.push_back(regs_[k].lane_endpoint());
  return lanes;
}

void Admission::run(const std::function<void()>& before_poll,
                    const std::function<void()>& after_poll) {
  const auto& names = scheme_.cut().names;
  const auto deadline = Clock::now() + o_.join_timeout;
  std::size_t count = 0;
  while (count < names.size()) {
    before_poll();
    const auto now = Clock::now();
    if (now >= deadline) {
      std::vector<std::string> absent, silent;
      for (std::size_t k = 0; k < names.size(); ++k) {
        if (registered_[k]) continue;
        (link_.joined(names[k]) ? silent : absent).push_back(names[k]);
      }
      throw StopRun(join_timeout_stop(absent, silent, o_.join_timeout, link_.endpoint()));
    }
    auto in = link_.poll(std::min<std::chrono::milliseconds>(
        100ms, std::chrono::ceil<std::chrono::milliseconds>(deadline - now)));
    drop_silent_unregistered();
    after_poll();
    link_.check_alive();
    if (!in) continue;
    const int k = index_of(in->domain);
    const auto& e = in->envelope;
    if (e.has_error()) throw StopRun(remote_error_stop(in->domain, e.error()));
    if (!e.has_registration() || registered_[static_cast<std::size_t>(k)]) {
      throw StopRun(
          protocol_stop(in->domain, fmt::format("domain '{}' sent a {} before its Setup; expected "
                                                "one Register",
                                                in->domain, wire::body_name(e))));
    }
    try {
      scheme_.check_register(k, e.registration());
    } catch (const ModelError& x) {
      throw StopRun(Stop{kExitInput,
                         wire::ERROR_CODE_MODEL,
                         {in->domain},
                         fmt::format("coordinator: {}", x.what())});
    }
    regs_[static_cast<std::size_t>(k)] = e.registration();
    registered_[static_cast<std::size_t>(k)] = true;
    link_.seal(in->domain);  // the run counts on this session: no second daemon for it
    ++count;
  }
}

/// A domain that said Hello but has been silent for the peer timeout without registering (a
/// daemon that died or hangs during its start, or a peer that only said Hello) loses its session
/// and the domain waits for a daemon again, up to the join timeout; the waiting coordinator goes
/// on. A registered domain that goes silent stops the run (check_alive()): the others' Setups
/// depend on it.
void Admission::drop_silent_unregistered() {
  for (const auto& d : link_.dead_peers()) {
    const int k = index_of(d);
    if (k < 0 || registered_[static_cast<std::size_t>(k)]) continue;
    link_.drop(d, wire::ERROR_CODE_TIMEOUT,
               fmt::format("domain '{}' said Hello and then nothing for {:.1f} s (peer timeout), "
                           "no Register: its session is dropped and the domain waits for a daemon "
                           "until the join timeout ({:.1f} s after the start)",
                           d, std::chrono::duration<double>(o_.session.peer_timeout).count(),
                           std::chrono::duration<double>(o_.join_timeout).count()));
  }
}

}  // namespace crashlink::coordinator
