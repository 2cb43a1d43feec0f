#include "solver/signal/hic.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "solver/signal/sampling.h"

namespace crashlink::signal {

namespace {

constexpr double kWindowSlack = 1e-9;  // relative: t[j] - t[i] <= W (1 + slack)

void check_inputs(std::span<const double> time_s, std::span<const double> accel_g,
                  double max_window_s) {
  check_signal(time_s, accel_g, "HIC input");
  if (!(max_window_s > 0.0)) {
    throw InputError(
        fmt::format("HIC: window {} s; give a positive window (0.015 for HIC15)", max_window_s));
  }
}

/// HIC of one window from its integral I = int a dt [g s] and length dt [s]: dt * (I/dt)^2.5.
double hic_of(double integral_g_s, double dt_s) {
  return dt_s * std::pow(integral_g_s / dt_s, 2.5);
}

}  // namespace

HicResult hic(std::span<const double> time_s, std::span<const double> accel_g,
              double max_window_s) {
  check_inputs(time_s, accel_g, max_window_s);
  const std::size_t n = time_s.size();
  // Cumulative trapezoid integral: C[k] = int_{t0}^{t_k} a dt, so int_{t_i}^{t_j} = C[j] - C[i].
  std::vector<double> c(n, 0.0);
  for (std::size_t k = 1; k < n; ++k) {
    c[k] = c[k - 1] + 0.5 * (accel_g[k - 1] + accel_g[k]) * (time_s[k] - time_s[k - 1]);
  }
  const double w = max_window_s * (1.0 + kWindowSlack);
  // Maximise HIC^2 = I^5 / dt^3 (monotone in HIC for I > 0): no pow in the O(n w) loop.
  double best = 0.0;
  std::size_t best_i = 0, best_j = 0;
  std::size_t j_end = 0;  // one past the last j with t[j] - t[i] <= w; non-decreasing in i
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (j_end < i + 1) j_end = i + 1;
    while (j_end < n && time_s[j_end] - time_s[i] <= w) ++j_end;
    const double ci = c[i], ti = time_s[i];
    double row_best = 0.0;
    std::size_t row_j = 0;
    for (std::size_t j = i + 1; j < j_end; ++j) {
      const double integral = c[j] - ci;
      const double dt = time_s[j] - ti;
      const double i2 = integral * integral;
      const double score = integral > 0.0 ? i2 * i2 * integral / (dt * dt * dt) : 0.0;
      if (score > row_best) {
        row_best = score;
        row_j = j;
      }
    }
    if (row_best > best) {
      best = row_best;
      best_i = i;
      best_j = row_j;
    }
  }
  if (best <= 0.0) return HicResult{0.0, time_s[0], time_s[0]};
  const double dt = time_s[best_j] - time_s[best_i];
  return HicResult{hic_of(c[best_j] - c[best_i], dt), time_s[best_i], time_s[best_j]};
}

HicResult hic_reference(std::span<const double> time_s, std::span<const double> accel_g,
                        double max_window_s) {
  check_inputs(time_s, accel_g, max_window_s);
  const std::size_t n = time_s.size();
  const double w = max_window_s * (1.0 + kWindowSlack);
  HicResult best{0.0, time_s[0], time_s[0]};
  for (std::size_t i = 0; i + 1 < n; ++i) {
    for (std::size_t j = i + 1; j < n && time_s[j] - time_s[i] <= w; ++j) {
      double integral = 0.0;
      for (std::size_t k = i + 1; k <= j; ++k) {
        integral += 0.5 * (accel_g[k - 1] + accel_g[k]) * (time_s[k] - time_s[k - 1]);
      }
      if (integral <= 0.0) continue;
      const double value = hic_of(integral, time_s[j] - time_s[i]);
      if (value > best.hic) best = HicResult{value, time_s[i], time_s[j]};
    }
  }
  return best;
}

}  // namespace crashlink::signal
