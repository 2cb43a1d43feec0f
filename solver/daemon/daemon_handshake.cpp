#include "solver/daemon/daemon_handshake.h"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "core/log_escape.h"

namespace crashlink::daemon {

wire::Envelope register_message(const coupling::DomainScheme& scheme,
                                const coupling::DomainSchemeOptions& options,
                                std::int64_t ticks_per_second,
                                const std::vector<coupling::Tick>& checkpoint_instants,
                                const OfferedLane& lane) {
  const auto& s = scheme.solver();
  const auto& sub = s.model();
  wire::Envelope e;
  auto* r = e.mutable_registration();
  r->set_stable_step_ticks(coupling::proposal_ticks(s, options, ticks_per_second));
  r->set_stable_step_s(s.dt_s());
  r->set_own_step_ticks(coupling::own_step_ticks(s, options.max_step_s, ticks_per_second));
  r->set_end_time_s(sub.controls.end_time_s);
  r->set_end_time_ticks(static_cast<std::int64_t>(
      std::llround(sub.controls.end_time_s * static_cast<double>(ticks_per_second))));
  r->set_elements(static_cast<std::int64_t>(sub.element_count()));
  for (const auto t : checkpoint_instants) r->add_checkpoint_ticks(t);
  r->set_lane_endpoint(lane.endpoint);
  r->set_lane_public_key(lane.public_key);
  scheme.fill_register(*r);
  return e;
}

void check_scheme(const wire::Setup& setup, const std::string& domain, const std::string& scheme) {
  if (setup.scheme() == scheme) return;
  throw ProtocolError(
      "coordinator",
      fmt::format("the coordinator runs the '{}' scheme, but domain '{}' was started for '{}': "
                  "start crashlink-solver and crashlink-coordinator with the same --coupling",
                  core::log_escape(setup.scheme()), domain, scheme));
}

}  // namespace crashlink::daemon
