// Fixed nested steps of a coupled run (nested_steps.h).
#include "coupling/nested_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/errors.h"

namespace crashlink::coupling {

namespace {
constexpr double kShrink = 0.01;  ///< see the shrink rule in nested_steps()

std::string name_of(const std::vector<std::string>& names, std::size_t k) {
  std::string r(1, k < names.size() ? '\'' : '#');
  r.append(k < names.size() ? names[k] : std::to_string(k));
  if (k < names.size()) r.push_back('\'');
  return r;
}

/// a * b, or a ModelError when it leaves the tick range (proposals near 2^63 ticks, or substep
/// counts whose product does: no whole-tick plan exists).
std::int64_t times(std::int64_t a, std::int64_t b, const char* what) {
  std::int64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r))
    throw ModelError("steps: " + std::string(what) + " " + std::to_string(a) + " x " +
                     std::to_string(b) +
                     " exceeds the tick range (2^63 ticks); fix: step "
                     "proposals far below 2^63 ticks (a smaller ticks_per_second) or fewer "
                     "substeps between the domains");
  return r;
}

/// lcm(a, b) for a, b >= 1, without overflow (ModelError as times()).
std::int64_t lcm_of(std::int64_t a, std::int64_t b) {
  return times(a / std::gcd(a, b), b, "the lcm of the substep counts");
}
}  // namespace

StepPlan nested_steps(const std::vector<Tick>& proposal,
                      const std::vector<std::pair<int, int>>& links, bool common,
                      const std::vector<std::string>& names) {
  const std::size_t nd = proposal.size();
  StepPlan plan;
  Tick smallest = 0, largest = 0;
  for (Tick p : proposal)
    if (p > 0) {
      smallest = smallest == 0 ? p : std::min(smallest, p);
      largest = std::max(largest, p);
    }
  if (smallest == 0)
    throw ModelError(
        "steps: no domain limits the step (every domain holds rigid bodies only); give "
        "controls.dt_max or a deformable part");
  plan.n.assign(nd, 1);
  plan.step.assign(nd, smallest);
  if (common || nd == 0) {
    plan.base = smallest;
    return plan;
  }
  // Kahn's order over coarse -> fine links, the largest proposal first among the ready domains.
  std::vector<std::vector<std::size_t>> fine_of(nd), coarse_of(nd);
  std::vector<int> pending(nd, 0);
  for (const auto& [c, f] : links) {
    if (c < 0 || f < 0 || static_cast<std::size_t>(c) >= nd || static_cast<std::size_t>(f) >= nd)
      throw ModelError("steps: link (" + std::to_string(c) + ", " + std::to_string(f) +
                       ") names a domain outside 0.." + std::to_string(nd - 1));
    fine_of[static_cast<std::size_t>(c)].push_back(static_cast<std::size_t>(f));
    coarse_of[static_cast<std::size_t>(f)].push_back(static_cast<std::size_t>(c));
    ++pending[static_cast<std::size_t>(f)];
  }
  const auto limit = [&](std::size_t k) { return proposal[k] > 0 ? proposal[k] : largest; };
  std::vector<std::uint8_t> done(nd, 0);
  Tick base = largest;
  for (std::size_t placed = 0; placed < nd; ++placed) {
    std::size_t pick = nd;
    for (std::size_t k = 0; k < nd; ++k)
      if (!done[k] && pending[k] == 0 && (pick == nd || limit(k) > limit(pick))) pick = k;
    if (pick == nd) {
      std::string cycle;
      for (std::size_t k = 0; k < nd; ++k)
        if (!done[k]) {
          if (!cycle.empty()) cycle.append(", ");
          cycle.append(name_of(names, k));
        }
      throw ModelError("steps: the coarse -> fine links between " + cycle +
                       " form a cycle; no nested steps exist. Fix: re-cut the domains");
    }
    std::int64_t L = 1;
    for (auto c : coarse_of[pick]) L = lcm_of(L, plan.n[c]);
    const std::int64_t per = times(limit(pick), L, "a step proposal times its substep count");
    // ceil(base / (limit L)) in integers (base + per - 1 could leave the tick range)
    std::int64_t need = std::max<std::int64_t>(1, base / per + (base % per != 0 ? 1 : 0));
    // A ratio just above a whole number k (within kShrink) costs one substep more than it is
    // worth: shrink the base period to k limit L instead (every step only gets smaller).
    if (need > 1 && static_cast<double>(base) <= (1.0 + kShrink) * static_cast<double>(need - 1) *
                                                     static_cast<double>(per)) {
      --need;
      base = need * per;
    }
    plan.n[pick] = times(L, need, "a substep count");
    done[pick] = 1;
    for (auto f : fine_of[pick]) --pending[f];
  }
  std::int64_t all = 1;
  for (auto n : plan.n) all = lcm_of(all, n);
  if (all > base / 1000)
    throw ModelError("steps: the substep counts need a base period divisible by " +
                     std::to_string(all) + " ticks, more than 0.1 % of the largest step (" +
                     std::to_string(base) + " ticks); fix: a larger ticks_per_second");
  plan.base = (base / all) * all;
  // n >= base / limit, so base / n <= limit: no step exceeds its proposal.
  for (std::size_t k = 0; k < nd; ++k) plan.step[k] = plan.base / plan.n[k];
  return plan;
}

Tick aligned_end(const StepPlan& plan, Tick end) {
  if (plan.base < 1 || end <= 0) return end;
  // Every domain lands on the multiples of lcm(steps) = base / gcd(n), the first common instant
  // (base itself only when some domain takes one step per base period).
  std::int64_t g = 0;
  for (const auto n : plan.n) g = std::gcd(g, n);
  const Tick period = g > 0 ? plan.base / g : plan.base;
  const Tick k = end / period + (end % period != 0 ? 1 : 0);
  if (k > std::numeric_limits<Tick>::max() / period)
    throw ModelError("nested steps: the end time " + std::to_string(end) +
                     " ticks rounded up to the common period " + std::to_string(period) +
                     " ticks of every step leaves the tick range");
  return k * period;
}

Tick aligned_end(const StepPlan& plan, double end_s, std::int64_t ticks_per_second) {
  return aligned_end(
      plan, static_cast<Tick>(std::llround(end_s * static_cast<double>(ticks_per_second))));
}

}  // namespace crashlink::coupling
