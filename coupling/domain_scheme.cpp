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

double own_step_s(const integration::Solver& s, double max_step_s) {
  const double dt = s.step_proposal();
  return max_step_s > 0.0 ? std::min(dt, max_step_s) : dt;
}

std::int64_t own_step_ticks(const integration::Solver& s, double max_step_s,
                            std::int64_t ticks_per_second) {
  const double dt = own_step_s(s, max_step_s);
  if (!std::isfinite(dt) || dt >= 1e3 || !(dt * static_cast<double>(ticks_per_second) >= 1.0))
    return 0;
  return TickClock(ticks_per_second).step_to_ticks(dt);
}

}  // namespace crashlink::coupling
