#include "solver/signal/channel_filter.h"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "solver/signal/cfc_filter.h"

namespace crashlink::signal {

FilteredChannels filter_channels(std::span<const double> time_s,
                                 std::vector<std::vector<double>> channels, int cfc,
                                 const std::string& what) {
  if (cfc != 0 && !is_cfc_class(cfc)) {
    throw InputError(fmt::format("{}: CFC {}: use 1000, 600, 180, 60 or 0 (none)", what, cfc));
  }
  for (const auto& ch : channels) check_signal(time_s, ch, what);
  FilteredChannels f;
  f.cfc = cfc;
  f.input = sampling_of(time_s);
  f.time_s.assign(time_s.begin(), time_s.end());
  if (cfc != 0 && !f.input.uniform()) {
    // J211/1 filters uniformly sampled channels: resample every channel to the mean step.
    std::vector<double> t;
    for (auto& ch : channels) ch = resample_linear(time_s, ch, f.input.mean_step_s, &t);
    f.time_s = std::move(t);
    f.resampled = true;
  }
  if (cfc != 0) {
    const double step = sampling_of(f.time_s).mean_step_s;
    for (auto& ch : channels) ch = cfc_filter(ch, step, cfc);
  }
  f.channels = std::move(channels);
  return f;
}

std::vector<std::vector<double>> xyz_channels(std::span<const double> xyz) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::vector<double>> out(3, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) out[c][i] = xyz[3 * i + c];
  return out;
}

std::vector<double> channel_resultant(const std::vector<std::vector<double>>& xyz, double scale) {
  const std::size_t n = xyz.empty() ? 0 : xyz[0].size();
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] =
        scale * std::sqrt(xyz[0][i] * xyz[0][i] + xyz[1][i] * xyz[1][i] + xyz[2][i] * xyz[2][i]);
  return out;
}

}  // namespace crashlink::signal
