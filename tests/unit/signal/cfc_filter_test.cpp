// SAE J211/1 CFC filter: gain against the CFC 1000 corridor, zero phase, start-up, bad input.
//
// Corridor points (SAE J211/1 Table 1 and Figure 1, CFC 1000: F_L = 0.1 Hz, F_H = 1000 Hz,
// F_N = 1650 Hz; limits a = +/-0.5 dB, b = +0.5/-1 dB at F_H, c = +0.5/-4 dB at F_N), with the
// stop band as the brief of issue 3 states it (upper limit falling at -40 dB/decade from +0.5 dB
// at F_N, and <= -30 dB at 5000 Hz). Between F_L and F_H the lower limit is taken as -0.5 dB
// (the stricter end of the a..b line). Verify against the standard's figure before relying on
// the stop-band points.
#include "solver/signal/cfc_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"

namespace crashlink::signal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct CorridorPoint {
  double f_Hz, lower_dB, upper_dB;
};

double upper_stop_band(double f_Hz) {
  return 0.5 - 40.0 * std::log10(f_Hz / 1650.0);
}

const std::vector<CorridorPoint>& cfc1000_corridor() {
  static const std::vector<CorridorPoint> points{
      {0.1, -0.5, 0.5},
      {10.0, -0.5, 0.5},
      {100.0, -0.5, 0.5},
      {500.0, -0.5, 0.5},
      {1000.0, -1.0, 0.5},
      {1650.0, -4.0, 0.5},
      {3300.0, -kInf, upper_stop_band(3300.0)},
      {5000.0, -kInf, -30.0},
  };
  return points;
}

double db(double gain) {
  return 20.0 * std::log10(gain);
}

/// Gain of cfc_filter at f measured on a unit sine: 40 s at fs, projection onto sin and cos over
/// the middle 10 s (a whole number of periods for every corridor frequency at 50 kHz).
double measured_gain(double f_Hz, double fs_Hz, int cfc) {
  const auto n = static_cast<std::size_t>(40.0 * fs_Hz);
  const auto w = static_cast<std::size_t>(10.0 * fs_Hz);
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = std::sin(2.0 * std::numbers::pi * f_Hz * static_cast<double>(k) / fs_Hz);
  }
  const std::vector<double> y = cfc_filter(x, 1.0 / fs_Hz, cfc);
  double s = 0.0, c = 0.0;
  for (std::size_t k = (n - w) / 2; k < (n + w) / 2; ++k) {
    const double phase = 2.0 * std::numbers::pi * f_Hz * static_cast<double>(k) / fs_Hz;
    s += y[k] * std::sin(phase);
    c += y[k] * std::cos(phase);
  }
  return 2.0 / static_cast<double>(w) * std::hypot(s, c);
}

TEST(CfcFilter, Cfc1000GainInsideTheJ211Corridor) {
  const double fs = 50000.0;
  for (const CorridorPoint& p : cfc1000_corridor()) {
    const double g = measured_gain(p.f_Hz, fs, 1000);
    const double analytic = cfc_gain(1000, 1.0 / fs, p.f_Hz);
    std::printf(
        "CFC 1000 at %g kHz: %7.1f Hz  measured %9.4f dB  analytic %9.4f dB  corridor "
        "[%g, %g] dB\n",
        fs / 1e3, p.f_Hz, db(g), db(analytic), p.lower_dB, p.upper_dB);
    EXPECT_NEAR(db(g), db(analytic), 0.01) << p.f_Hz << " Hz";
    EXPECT_GE(db(g), p.lower_dB) << p.f_Hz << " Hz";
    EXPECT_LE(db(g), p.upper_dB) << p.f_Hz << " Hz";
  }
}

TEST(CfcFilter, Cfc1000CorridorAtOtherSampleRates) {
  // The analytic response (checked against the filter above) at 10, 20 and 100 kHz: every corridor
  // point below the Nyquist frequency.
  for (double fs : {10000.0, 20000.0, 100000.0}) {
    for (const CorridorPoint& p : cfc1000_corridor()) {
      if (p.f_Hz >= fs / 2) continue;
      const double g = db(cfc_gain(1000, 1.0 / fs, p.f_Hz));
      EXPECT_GE(g, p.lower_dB) << p.f_Hz << " Hz at " << fs << " Hz";
      EXPECT_LE(g, p.upper_dB) << p.f_Hz << " Hz at " << fs << " Hz";
    }
  }
}

TEST(CfcFilter, MinusThreeDecibelsNearFN) {
  // The double pass of the 2-pole corner 2.0775 CFC is -3 dB at 0.8022 x 2077.5 = 1667 Hz (analog);
  // bisect the digital response at 50 kHz and 20 kHz: within 5 % of F_N = 1650 Hz.
  for (double fs : {50000.0, 20000.0}) {
    double lo = 1000.0, hi = 3000.0;
    while (hi - lo > 1e-3) {
      const double mid = 0.5 * (lo + hi);
      (db(cfc_gain(1000, 1.0 / fs, mid)) > -3.0 ? lo : hi) = mid;
    }
    std::printf("CFC 1000 at %g kHz: -3 dB at %.1f Hz\n", fs / 1e3, lo);
    EXPECT_NEAR(lo, 1650.0, 0.05 * 1650.0);
  }
}

TEST(CfcFilter, ZeroPhaseSymmetricPulseStaysSymmetric) {
  // Half-sine of 4 ms centred at 50 ms in a 100 ms record at 20 kHz, CFC 180 and CFC 1000.
  const double fs = 20000.0;
  const std::size_t n = 2001, centre = 1000;
  std::vector<double> x(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = (static_cast<double>(k) - static_cast<double>(centre)) / fs;
    if (std::abs(t) <= 0.002) x[k] = 100.0 * std::cos(std::numbers::pi * t / 0.004);
  }
  for (int cfc : {180, 1000}) {
    const std::vector<double> y = cfc_filter(x, 1.0 / fs, cfc);
    const auto peak = static_cast<std::size_t>(std::max_element(y.begin(), y.end()) - y.begin());
    EXPECT_EQ(peak, centre) << "CFC " << cfc;
    double asymmetry = 0.0;
    for (std::size_t k = 1; k < 400; ++k) {
      asymmetry = std::max(asymmetry, std::abs(y[centre + k] - y[centre - k]));
    }
    EXPECT_LT(asymmetry, 1e-9 * y[centre]) << "CFC " << cfc;
    // The test has teeth: one 2-pole pass alone delays the peak.
    const std::vector<double> one = cfc_pass(x, cfc_coefficients(cfc, 1.0 / fs));
    const auto late =
        static_cast<std::size_t>(std::max_element(one.begin(), one.end()) - one.begin());
    EXPECT_GT(late, centre) << "CFC " << cfc;
    std::printf(
        "CFC %d: peak %.4f g at sample %zu (input 100 g at %zu), asymmetry %.2e; one pass: "
        "peak at sample %zu\n",
        cfc, y[peak], peak, centre, asymmetry, late);
  }
}

TEST(CfcFilter, StartUpKeepsConstantsAndRamps) {
  // Odd reflection at both ends: a constant and a ramp pass unchanged (to round-off), end samples
  // included.
  const double T = 1e-4;
  std::vector<double> c(500, 42.0), r(500);
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = 3.0 + 0.5 * static_cast<double>(k);
  for (int cfc : {60, 180, 600, 1000}) {
    const auto yc = cfc_filter(c, T, cfc);
    const auto yr = cfc_filter(r, T, cfc);
    for (std::size_t k = 0; k < c.size(); ++k) {
      ASSERT_NEAR(yc[k], 42.0, 1e-9) << "CFC " << cfc << " sample " << k;
      ASSERT_NEAR(yr[k], r[k], 1e-7) << "CFC " << cfc << " sample " << k;
    }
  }
}

TEST(CfcFilter, DcGainIsOne) {
  for (int cfc : {60, 180, 600, 1000}) {
    const CfcCoefficients k = cfc_coefficients(cfc, 1e-4);
    EXPECT_NEAR((k.a0 + k.a1 + k.a2) / (1.0 - k.b1 - k.b2), 1.0, 1e-12);
    EXPECT_NEAR(cfc_gain(cfc, 1e-4, 0.0), 1.0, 1e-12);
  }
}

TEST(CfcFilter, BadInput) {
  EXPECT_THROW(cfc_coefficients(100, 1e-4), InputError);  // not a class
  EXPECT_THROW(cfc_coefficients(1000, 0.0), InputError);
  EXPECT_THROW(cfc_coefficients(1000, 1.0 / 4000.0), InputError);  // 4 kHz: too slow for CFC 1000
  const std::vector<double> t{0.0, 1e-4, 2e-4, 3.5e-4, 4.5e-4}, x{0, 1, 2, 3, 4};
  try {
    cfc_filter(t, x, 1000, "probe head");
    FAIL() << "non-uniform sampling accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("probe head"), std::string::npos) << m;
    EXPECT_NE(m.find("uniform"), std::string::npos) << m;
    EXPECT_NE(m.find("0.0001 to 0.00015"), std::string::npos) << m;
  }
  // Uniform within the tolerance (time stamps with few digits) is accepted.
  const std::vector<double> t2{0.0, 1.0e-4, 2.00001e-4, 3.0e-4, 4.0e-4};
  EXPECT_EQ(cfc_filter(t2, x, 1000).size(), x.size());
}

}  // namespace
}  // namespace crashlink::signal
