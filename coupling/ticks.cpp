#include "coupling/ticks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"

namespace crashlink::coupling {

namespace {
constexpr std::int64_t kMaxExactInteger = std::int64_t{1} << 53;  // doubles hold every int up to it
constexpr double kMaxTicks = 4611686018427387904.0;               // 2^62: headroom for t + dt
}  // namespace

TickClock::TickClock(std::int64_t ticks_per_second) : ticks_per_second_(ticks_per_second) {
  if (ticks_per_second < 1 || ticks_per_second > kMaxExactInteger) {
    throw ModelError(fmt::format(
        "tick: ticks_per_second = {} is out of range [1, 2^53]; fix: use e.g. 1e15 (1 fs ticks)",
        ticks_per_second));
  }
}

double TickClock::to_seconds(Tick n) const {
  // One correctly rounded division of two exact doubles (for |n| <= 2^53).
  return static_cast<double>(n) / static_cast<double>(ticks_per_second_);
}

Tick TickClock::to_ticks(double t_s) const {
  if (!std::isfinite(t_s) || t_s < 0.0) {
    throw NumericalError(fmt::format(
        "tick: time or step {} s cannot be converted to ticks (negative or not finite); the "
        "solver that produced it has blown up or the scenario gives a negative time",
        t_s));
  }
  const double x = t_s * static_cast<double>(ticks_per_second_);
  if (x >= kMaxTicks) {
    throw ModelError(fmt::format(
        "tick: {} s is {} ticks of 1/{} s, beyond 2^62; fix: a smaller ticks_per_second", t_s, x,
        ticks_per_second_));
  }
  // t_s carries at most half an ulp of representation error and the product one more rounding:
  // a value that close to an integer is that integer (to_ticks(): the snap exception).
  const double nearest = std::nearbyint(x);
  const double snap = kSnapUlps * std::numeric_limits<double>::epsilon() * std::max(1.0, x);
  const double n = std::abs(x - nearest) <= snap ? nearest : std::floor(x);
  return static_cast<Tick>(n);
}

Tick TickClock::step_to_ticks(double dt_s) const {
  const Tick n = to_ticks(dt_s);
  if (n < 1) {
    throw ModelError(fmt::format(
        "tick: step {} s is shorter than one tick (1/{} s); fix: a larger ticks_per_second", dt_s,
        ticks_per_second_));
  }
  return n;
}

}  // namespace crashlink::coupling
