#pragma once
// Linear interpolation in time of a partner's interface vector, [10] of Bourel 2005 (docs/design.md
// §2.3; also u_ref(t) of the drift correction [11], §2.4):
//   x(t) = x(t_l^j) (t_l^{j+1} - t) / (t_l^{j+1} - t_l^j) + x(t_l^{j+1}) (t - t_l^j) / (...)
// with the exact weight of a Bracket (schedule.h). Coinciding instants return the state bit for
// bit (no interpolation: equal steps reproduce the mono-scale coupling exactly).
// Layout: flat arrays of equal length n (n = 3 x interface nodes, xyz interleaved); out may alias
// neither input.
#include <span>

#include "coupling/schedule.h"

namespace crashlink::coupling {

/// out[i] = lower[i] * w.lower_factor() + upper[i] * w.upper_factor(). Sizes must match
/// (throws crashlink::ModelError otherwise).
void interpolate(std::span<const double> lower, std::span<const double> upper, Weight w,
                 std::span<double> out);

}  // namespace crashlink::coupling
