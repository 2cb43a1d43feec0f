#pragma once
// The median of a list of measurements (benchmarks' and Table 1's repeated runs).
#include <algorithm>
#include <limits>
#include <vector>

namespace crashlink::core {

/// The middle value of x, the mean of the middle two for an even count; NaN for an empty list.
inline double median(std::vector<double> x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 == 1 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

}  // namespace crashlink::core
