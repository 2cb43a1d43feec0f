#include "solver/signal/sampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace crashlink::signal {

void check_signal(std::span<const double> time_s, std::span<const double> values,
                  const std::string& what, std::size_t min_samples) {
  if (time_s.size() != values.size()) {
    throw InputError(fmt::format("{}: {} time instants but {} values (give one value per instant)",
                                 what, time_s.size(), values.size()));
  }
  if (time_s.size() < min_samples) {
    throw InputError(
        fmt::format("{}: {} samples; at least {} are needed", what, time_s.size(), min_samples));
  }
  for (std::size_t k = 0; k < time_s.size(); ++k) {
    if (!std::isfinite(time_s[k]) || !std::isfinite(values[k])) {
      throw InputError(
          fmt::format("{}: sample {} is not finite (time {} s, value {}); remove it "
                      "or fix the source",
                      what, k, time_s[k], values[k]));
    }
    if (k > 0 && !(time_s[k] > time_s[k - 1])) {
      throw InputError(
          fmt::format("{}: time is not increasing at sample {}: t[{}] = {} s, "
                      "t[{}] = {} s (sort the samples and drop duplicate instants)",
                      what, k, k - 1, time_s[k - 1], k, time_s[k]));
    }
  }
}

Sampling sampling_of(std::span<const double> time_s) {
  CRASHLINK_ASSERT(time_s.size() >= 2);
  Sampling s;
  const std::size_t n = time_s.size();
  s.mean_step_s = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);
  s.min_step_s = time_s[1] - time_s[0];
  s.max_step_s = s.min_step_s;
  for (std::size_t k = 2; k < n; ++k) {
    const double h = time_s[k] - time_s[k - 1];
    s.min_step_s = std::min(s.min_step_s, h);
    s.max_step_s = std::max(s.max_step_s, h);
  }
  return s;
}

std::vector<double> resample_linear(std::span<const double> time_s, std::span<const double> values,
                                    double step_s, std::vector<double>* uniform_time_s,
                                    std::size_t components) {
  const std::size_t n = time_s.size();
  const std::size_t m = components == 0 ? 1 : components;
  if (n < 2 || values.size() != m * n || !(step_s > 0.0)) {
    throw InputError(
        fmt::format("resample_linear: {} instants, {} values of {} components, step "
                    "{} s (need >= 2 instants, one value per component and instant "
                    "and a positive step)",
                    n, values.size(), m, step_s));
  }
  const double t0 = time_s[0];
  const double span = time_s[n - 1] - t0;
  const auto count = static_cast<std::size_t>(std::floor(span / step_s * (1.0 + 1e-9))) + 1;
  std::vector<double> out(count * m);
  if (uniform_time_s) uniform_time_s->resize(count);
  std::size_t j = 0;  // time_s[j] <= t < time_s[j+1]
  for (std::size_t k = 0; k < count; ++k) {
    const double t = std::min(t0 + static_cast<double>(k) * step_s, time_s[n - 1]);
    while (j + 2 < n && time_s[j + 1] <= t) ++j;
    const double w = (t - time_s[j]) / (time_s[j + 1] - time_s[j]);
    for (std::size_t c = 0; c < m; ++c) {
      out[k * m + c] = (1.0 - w) * values[j * m + c] + w * values[(j + 1) * m + c];
    }
    if (uniform_time_s) (*uniform_time_s)[k] = t;
  }
  return out;
}

std::vector<double> resultant(std::span<const double> xyz, double scale) {
  CRASHLINK_ASSERT(xyz.size() % 3 == 0);
  std::vector<double> out(xyz.size() / 3);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double x = xyz[3 * k], y = xyz[3 * k + 1], z = xyz[3 * k + 2];
    out[k] = scale * std::sqrt(x * x + y * y + z * z);
  }
  return out;
}

}  // namespace crashlink::signal
