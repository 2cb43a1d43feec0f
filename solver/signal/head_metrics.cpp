#include "solver/signal/head_metrics.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.h"
#include "solver/signal/channel_filter.h"

namespace crashlink::signal {

HeadMetrics head_metrics(std::span<const double> time_s, std::vector<std::vector<double>> channel,
                         double to_g, int cfc, const std::string& what) {
  if (channel.size() != 1 && channel.size() != 3) {
    throw InputError(fmt::format("{}: {} channels; give 1 (the resultant) or 3 (x, y, z)", what,
                                 channel.size()));
  }
  FilteredChannels f = filter_channels(time_s, std::move(channel), cfc, what);
  HeadMetrics m;
  m.cfc = cfc;
  m.min_step_s = f.input.min_step_s;
  m.max_step_s = f.input.max_step_s;
  m.mean_step_s = f.input.mean_step_s;
  m.resampled = f.resampled;
  m.time_s = std::move(f.time_s);
  if (f.channels.size() == 3) {
    m.accel_g = channel_resultant(f.channels, to_g);
  } else {
    m.accel_g = std::move(f.channels[0]);
    for (double& a : m.accel_g) a *= to_g;
  }
  const auto peak = std::max_element(m.accel_g.begin(), m.accel_g.end());
  m.peak_g = *peak;
  m.peak_time_s = m.time_s[static_cast<std::size_t>(peak - m.accel_g.begin())];
  m.hic15 = hic(m.time_s, m.accel_g, kHic15Window_s);
  m.hic36 = hic(m.time_s, m.accel_g, kHic36Window_s);
  return m;
}

HeadMetrics head_metrics_xyz(std::span<const double> time_s, std::span<const double> accel_xyz_m_s2,
                             int cfc, const std::string& what) {
  const std::size_t n = time_s.size();
  if (accel_xyz_m_s2.size() != 3 * n) {
    throw InputError(
        fmt::format("{}: {} acceleration values for {} instants; expected 3 per instant", what,
                    accel_xyz_m_s2.size(), n));
  }
  return head_metrics(time_s, xyz_channels(accel_xyz_m_s2), 1.0 / kStandardGravity_m_s2, cfc, what);
}

}  // namespace crashlink::signal
