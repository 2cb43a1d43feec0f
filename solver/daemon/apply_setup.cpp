#include "solver/daemon/apply_setup.h"

#include <fmt/format.h>

#include "transport/errors.h"

namespace crashlink::daemon {

void apply_setup(const wire::Setup& setup, std::int64_t ticks_per_second, const std::string& domain,
                 std::vector<cosim::LayerPort>& ports) {
  if (setup.ticks_per_second() != ticks_per_second || setup.step_ticks() < 1) {
    throw ProtocolError(
        "coordinator",
        fmt::format("Setup for domain '{}' with step {} ticks at {} ticks per "
                    "second (Hello: {}); expected a step >= 1 at the Hello's tick",
                    domain, setup.step_ticks(), setup.ticks_per_second(), ticks_per_second));
  }
  for (auto& port : ports) {
    const wire::LayerInterface* found = nullptr;
    for (const auto& li : setup.layer_interfaces()) {
      if (li.index() == port.index) found = &li;
    }
    if (found == nullptr || found->fine_side() != port.fine_side ||
        found->partner() != port.partner) {
      throw ProtocolError(
          "coordinator",
          fmt::format("Setup for domain '{}' does not describe interface {} as this domain's cut "
                      "does ({} side, partner '{}'): do both read the same scenario?",
                      domain, port.index, port.fine_side ? "fine" : "coarse", port.partner));
    }
    // As LayerNetwork: the owner's step on the fine side; the coarse side needs none.
    if (port.fine_side) port.partner_step = found->partner_step_ticks();
  }
}

}  // namespace crashlink::daemon
