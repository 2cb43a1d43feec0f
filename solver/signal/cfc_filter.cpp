#include "solver/signal/cfc_filter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/errors.h"
#include "solver/signal/sampling.h"

namespace crashlink::signal {

namespace {
constexpr double kCornerPerCfc = 2.0775;  // J211/1 Appendix C: wd = 2 pi CFC 2.0775
constexpr double kStartUpPeriods = 4.0;   // padding length in periods of the 2-pole corner
}  // namespace

bool is_cfc_class(int cfc) {
  return cfc == 60 || cfc == 180 || cfc == 600 || cfc == 1000;
}

CfcCoefficients cfc_coefficients(int cfc, double sample_period_s) {
  if (!is_cfc_class(cfc)) {
    throw InputError(fmt::format(
        "CFC {}: not a channel frequency class of SAE J211/1; use 60, 180, 600 or 1000", cfc));
  }
  if (!(sample_period_s > 0.0) || !std::isfinite(sample_period_s)) {
    throw InputError(
        fmt::format("CFC {}: sample period {} s; it must be positive", cfc, sample_period_s));
  }
  const double wd = 2.0 * std::numbers::pi * cfc * kCornerPerCfc;  // J211/1 C
  const double half = wd * sample_period_s / 2.0;
  if (half >= 0.49 * std::numbers::pi) {
    throw InputError(fmt::format(
        "CFC {}: sample rate {:.6g} Hz is too low for the class (the 2-pole corner {:.6g} Hz must "
        "stay well below the Nyquist frequency); sample at >= {:.6g} Hz or use a lower class",
        cfc, 1.0 / sample_period_s, cfc * kCornerPerCfc, 10.0 * cfc));
  }
  const double wa = std::sin(half) / std::cos(half);  // J211/1 C (prewarping)
  const double wa2 = wa * wa;
  const double d = 1.0 + std::numbers::sqrt2 * wa + wa2;
  CfcCoefficients k;
  k.a0 = wa2 / d;
  k.a1 = 2.0 * k.a0;
  k.a2 = k.a0;
  k.b1 = -2.0 * (wa2 - 1.0) / d;
  k.b2 = (-1.0 + std::numbers::sqrt2 * wa - wa2) / d;
  return k;
}

double cfc_gain(int cfc, double sample_period_s, double frequency_Hz) {
  const CfcCoefficients k = cfc_coefficients(cfc, sample_period_s);
  // H2(z) = (a0 + a1 z^-1 + a2 z^-2) / (1 - b1 z^-1 - b2 z^-2); both passes: |H2|^2.
  const std::complex<double> z1 =
      std::polar(1.0, -2.0 * std::numbers::pi * frequency_Hz * sample_period_s);
  const std::complex<double> z2 = z1 * z1;
  const std::complex<double> h = (k.a0 + k.a1 * z1 + k.a2 * z2) / (1.0 - k.b1 * z1 - k.b2 * z2);
  return std::norm(h);
}

std::vector<double> cfc_pass(std::span<const double> x, const CfcCoefficients& k) {
  const std::size_t n = x.size();
  std::vector<double> y(n);
  for (std::size_t t = 0; t < n && t < 2; ++t) y[t] = x[t];  // start at rest on the input
  for (std::size_t t = 2; t < n; ++t) {
    y[t] = k.a0 * x[t] + k.a1 * x[t - 1] + k.a2 * x[t - 2] + k.b1 * y[t - 1] + k.b2 * y[t - 2];
  }
  return y;
}

std::vector<double> cfc_filter(std::span<const double> x, double sample_period_s, int cfc) {
  const CfcCoefficients k = cfc_coefficients(cfc, sample_period_s);
  const std::size_t n = x.size();
  if (n < 2) return std::vector<double>(x.begin(), x.end());
  const auto wanted = static_cast<std::size_t>(
      std::ceil(kStartUpPeriods / (kCornerPerCfc * cfc * sample_period_s)));
  const std::size_t pad = std::min(n - 1, wanted);
  // Odd reflection about each end: [2x0 - x[pad..1], x, 2x[n-1] - x[n-2..n-1-pad]].
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (std::size_t k2 = pad; k2 >= 1; --k2) ext.push_back(2.0 * x[0] - x[k2]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t k2 = 1; k2 <= pad; ++k2) ext.push_back(2.0 * x[n - 1] - x[n - 1 - k2]);
  std::vector<double> forward = cfc_pass(ext, k);
  std::reverse(forward.begin(), forward.end());
  std::vector<double> backward = cfc_pass(forward, k);
  std::reverse(backward.begin(), backward.end());
  return std::vector<double>(backward.begin() + static_cast<std::ptrdiff_t>(pad),
                             backward.begin() + static_cast<std::ptrdiff_t>(pad + n));
}

std::vector<double> cfc_filter(std::span<const double> time_s, std::span<const double> x, int cfc,
                               const std::string& what) {
  check_signal(time_s, x, what);
  const Sampling s = sampling_of(time_s);
  if (!s.uniform()) {
    throw InputError(fmt::format(
        "{}: the CFC {} filter (SAE J211/1) needs uniform sampling; the steps range from {:.6g} "
        "to {:.6g} s (mean {:.6g} s). Resample to a uniform step first (signal::resample_linear), "
        "or write history at a fixed interval",
        what, cfc, s.min_step_s, s.max_step_s, s.mean_step_s));
  }
  return cfc_filter(x, s.mean_step_s, cfc);
}

}  // namespace crashlink::signal
