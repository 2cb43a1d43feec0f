#pragma once
// The fixed steps of a coupled run (docs/design.md §2.6, §2.7): every domain steps at base / n_k
// ticks with a whole n_k, and at every interface the fine side's n is a multiple of the coarse
// side's, so the fine side lands on every coarse instant (the `layer` scheme needs its force on J
// there; docs/design.md §2.7: "do not shorten the last fine substep to land on T"). The rule:
// nested_steps; the common end instant: aligned_end.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "coupling/ticks.h"

namespace crashlink::coupling {

struct StepPlan {
  Tick base = 0;                ///< the common period: every domain lands on multiples of it
  std::vector<std::int64_t> n;  ///< [domains] substeps per base period
  std::vector<Tick> step;       ///< [domains] base / n
};

/// A non-integer ratio of stable steps r = H/h runs as ceil(r) equal fine substeps per coarse step
/// (the study's 'uniform' mode, coupling-study/layer-check/layer.py), the fine step H/ceil(r) <= h.
///   split: every domain at the global minimum proposal (n_k = 1).
///   multi: base = the largest proposal; domains in decreasing order of proposal (each interface's
///     coarse side before its fine side), n_k = the smallest multiple of L_k (the lcm of n over the
///     domains it is fine side to) with base / n_k <= proposal_k, except that a ratio within 1 %
///     above a whole number k shrinks base to k proposal_k L_k instead of taking one substep more
///     (steps only ever get smaller; 2.0000001 must not cost three substeps); then base is rounded
///     down to a multiple of lcm(n) ticks, so every step is a whole number of ticks and no step
///     exceeds its proposal.
/// Proposals are in ticks; a proposal <= 0 means "no limit" (a domain of rigid bodies only).
/// `links`: (coarse domain, fine domain) pairs. `common`: split mode (one step for all).
/// A link whose fine side has the larger proposal runs that side at its coarse side's step.
/// Throws ModelError when no domain has a limit, when the links form a cycle of coarse -> fine
/// (names the domains), or when lcm(n) exceeds base / 1000 (steps would lose more than 0.1 % to
/// rounding), or when a step times a substep count leaves the tick range (2^63 ticks).
StepPlan nested_steps(const std::vector<Tick>& proposal,
                      const std::vector<std::pair<int, int>>& links, bool common,
                      const std::vector<std::string>& names = {});

/// The end instant every domain of `plan` can stop at: `end` rounded up to a whole number of
/// lcm(steps) = base / gcd(n) (the first instant all domains land on). Throws ModelError when that
/// leaves the tick range.
Tick aligned_end(const StepPlan& plan, Tick end);
/// The same for the scenario's end time in seconds, rounded to the nearest tick first: what the
/// coordinator's Setup sends (Setup.end_time_ticks) and cosim::LayerNetwork applies.
Tick aligned_end(const StepPlan& plan, double end_s, std::int64_t ticks_per_second);

}  // namespace crashlink::coupling
