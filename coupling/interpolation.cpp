#include "coupling/interpolation.h"

#include <algorithm>

#include "core/errors.h"

namespace crashlink::coupling {

void interpolate(std::span<const double> lower, std::span<const double> upper, Weight w,
                 std::span<double> out) {
  if (lower.size() != upper.size() || lower.size() != out.size()) {
    throw ModelError(fmt::format(
        "interpolate [10]: vectors of sizes {}, {} and {}; the two states and the output must "
        "have the same length (3 x interface nodes)",
        lower.size(), upper.size(), out.size()));
  }
  CRASHLINK_ASSERT(w.den > 0 && w.num >= 0 && w.num <= w.den);
  if (w.num == 0) {  // t == t_l^j: the state itself
    std::copy(lower.begin(), lower.end(), out.begin());
    return;
  }
  if (w.num == w.den) {  // t == t_l^{j+1}
    std::copy(upper.begin(), upper.end(), out.begin());
    return;
  }
  const double c0 = w.lower_factor();  // (t_l^{j+1} - t) / (t_l^{j+1} - t_l^j)
  const double c1 = w.upper_factor();  // (t - t_l^j) / (t_l^{j+1} - t_l^j)
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = lower[i] * c0 + upper[i] * c1;  // [10]
}

}  // namespace crashlink::coupling
