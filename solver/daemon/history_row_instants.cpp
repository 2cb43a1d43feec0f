#include "solver/daemon/history_row_instants.h"

#include <cmath>
#include <limits>

namespace crashlink::daemon {

std::int64_t HistoryRowInstants::coarse_instant(double instant_s) const {
  const double k =
      std::floor(instant_s * static_cast<double>(tps_) / static_cast<double>(period_) + 1e-6);
  // past the last representable tick (a history interval of 1e20 s switches rows off): never
  if (!(k * static_cast<double>(period_) < 9.0e18)) return std::numeric_limits<std::int64_t>::max();
  return period_ * static_cast<std::int64_t>(k);
}

bool HistoryRowInstants::reads(std::int64_t T) {
  if (!(interval_s_ * static_cast<double>(tps_) > static_cast<double>(period_)))
    return true;  // a row in every coarse step (or every cycle)
  while (coarse_instant(row_s_) < T - 2 * period_ && row_s_ + interval_s_ != row_s_)
    row_s_ += interval_s_;
  for (double r = row_s_;; r += interval_s_) {
    const std::int64_t at = coarse_instant(r);
    if (at >= T) return at == T;
    if (r + interval_s_ == r) return false;  // the sum no longer moves (the recorder's neither)
  }
}

}  // namespace crashlink::daemon
