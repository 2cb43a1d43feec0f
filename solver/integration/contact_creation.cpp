#include "solver/integration/contact_creation.h"

#include <cmath>

namespace crashlink::integration {

ContactCreation contact_creation(std::span<const contact::ContactStep> steps) {
  ContactCreation c;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double created = created_energy_J(steps[k].energy_J);
    if (created == 0.0) continue;
    c.total_J += created;
    ++c.creating;
    if (created > c.worst_J || std::isnan(created)) {
      c.worst = k;
      c.worst_J = created;
      if (std::isnan(created)) break;
    }
  }
  return c;
}

}  // namespace crashlink::integration
