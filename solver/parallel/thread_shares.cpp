#include "solver/parallel/thread_shares.h"

#include <cmath>
#include <cstddef>

namespace crashlink::parallel {

std::vector<int> share_threads(const std::vector<double>& work, int cores) {
  std::vector<int> threads(work.size(), 1);
  const auto clean = [&](std::size_t d) {
    return std::isfinite(work[d]) && work[d] > 0.0 ? work[d] : 0.0;
  };
  for (int left = cores - static_cast<int>(work.size()); left > 0; --left) {
    std::size_t best = 0;
    double most = -1.0;
    for (std::size_t d = 0; d < work.size(); ++d) {
      const double per_thread = clean(d) / threads[d];
      if (per_thread > most) {
        most = per_thread;
        best = d;
      }
    }
    if (work.empty() || !(most > 0.0)) break;  // nothing left to speed up
    ++threads[best];
  }
  return threads;
}

}  // namespace crashlink::parallel
