#include "coupling/domain_scheme.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace crashlink::coupling {

std::int64_t proposal_ticks(const integration::Solver& s, const DomainSchemeOptions& o,
                            std::int64_t ticks_per_second) {
  double dt = s.dt_s();
  if (o.max_step_s > 0.0) dt = std::min(dt, o.max_step_s);
  if (!std::isfinite(dt)) return 0;
  const double x = std::floor(o.step_safety * dt * static_cast<double>(ticks_per_second));
  if (!(x >= 1.0) || x > 4.0e18) {
    throw ModelError(
        fmt::format("the stable step {:.6e} s is not a whole number of ticks of 1/{} s (at "
                    "least one)",
                    dt, ticks_per_second));
  }
  return static_cast<std::int64_t>(x);
}

}  // namespace crashlink::coupling
