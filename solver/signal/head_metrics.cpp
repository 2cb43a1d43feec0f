#include "solver/signal/head_metrics.h"

#include <fmt/format.h>

#include <algorithm>

#include "solver/core/errors.h"
#include "solver/signal/cfc_filter.h"
#include "solver/signal/sampling.h"

namespace crashlink::signal {

HeadMetrics head_metrics(std::span<const double> time_s, std::vector<std::vector<double>> channel,
                         double to_g, int cfc, const std::string& what) {
  if (channel.size() != 1 && channel.size() != 3) {
    throw InputError(fmt::format("{}: {} channels; give 1 (the resultant) or 3 (x, y, z)", what,
                                 channel.size()));
  }
  if (cfc != 0 && !is_cfc_class(cfc)) {
    throw InputError(fmt::format("{}: CFC {}: use 1000, 600, 180, 60 or 0 (none)", what, cfc));
  }
  for (const auto& ch : channel) check_signal(time_s, ch, what);
  HeadMetrics m;
  m.cfc = cfc;
  const Sampling s = sampling_of(time_s);
  m.min_step_s = s.min_step_s;
  m.max_step_s = s.max_step_s;
  m.mean_step_s = s.mean_step_s;
  m.time_s.assign(time_s.begin(), time_s.end());
  if (cfc != 0 && !s.uniform()) {
    // J211/1 filters uniformly sampled channels: resample every channel to the mean step.
    std::vector<double> t;
    for (auto& ch : channel) ch = resample_linear(time_s, ch, s.mean_step_s, &t);
    m.time_s = std::move(t);
    m.resampled = true;
  }
  if (cfc != 0) {
    const double step = sampling_of(m.time_s).mean_step_s;
    for (auto& ch : channel) ch = cfc_filter(ch, step, cfc);
  }
  if (channel.size() == 3) {
    std::vector<double> xyz(3 * m.time_s.size());
    for (std::size_t i = 0; i < m.time_s.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) xyz[3 * i + c] = channel[c][i];
    m.accel_g = resultant(xyz, to_g);
  } else {
    m.accel_g = std::move(channel[0]);
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
  std::vector<std::vector<double>> channel(3, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) channel[c][i] = accel_xyz_m_s2[3 * i + c];
  return head_metrics(time_s, std::move(channel), 1.0 / kStandardGravity_m_s2, cfc, what);
}

}  // namespace crashlink::signal
