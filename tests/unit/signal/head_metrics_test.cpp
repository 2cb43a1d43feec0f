// Head metrics of a 3-axis probe (solver/signal/head_metrics.h): the resultant of the three
// channels in g, its peak and HIC, against closed forms; the direction of the pulse does not
// matter; CFC 1000 keeps a 6 ms pulse; a bad input is refused.
#include "solver/signal/head_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "solver/signal/sampling.h"

namespace crashlink::signal {
namespace {

/// A half-sine of peak A [g], duration T [s] along the unit direction d, sampled every 10 us.
void half_sine_xyz(double A, double T, const double d[3], std::vector<double>& t,
                   std::vector<double>& xyz) {
  const double step = 1e-5;
  for (int k = 0; k <= 3000; ++k) {
    const double tk = k * step;
    const double a = (tk <= T) ? A * std::sin(std::numbers::pi * tk / T) : 0.0;
    t.push_back(tk);
    for (int c = 0; c < 3; ++c) xyz.push_back(a * kStandardGravity_m_s2 * d[c]);
  }
}

TEST(HeadMetrics, HalfSineInAnyDirectionMatchesTheOneDimensionalPulse) {
  // A half-sine along x, along -z and along an oblique unit vector: the resultant is the 1-D
  // pulse, so peak = A at T/2 and HIC15 = hic() of the 1-D pulse (itself checked against the
  // closed forms in hic_test.cpp), the same for the three directions.
  const double A = 150.0, T = 0.006;
  const double dirs[3][3] = {{1, 0, 0}, {0, 0, -1}, {0.6, -0.48, 0.64}};
  double first_hic = -1.0;
  for (const auto& d : dirs) {
    std::vector<double> t, xyz;
    half_sine_xyz(A, T, d, t, xyz);
    const HeadMetrics m = head_metrics_xyz(t, xyz, 0, "half-sine");
    EXPECT_NEAR(m.peak_g, A, 1e-9 * A);
    EXPECT_NEAR(m.peak_time_s, T / 2, 1e-9);
    std::vector<double> a(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) a[i] = A * std::sin(std::numbers::pi * t[i] / T);
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] > T) a[i] = 0.0;
    const double expected = hic(t, a, kHic15Window_s).hic;
    EXPECT_NEAR(m.hic15.hic, expected, 1e-9 * expected);
    if (first_hic < 0.0) first_hic = m.hic15.hic;
    EXPECT_NEAR(m.hic15.hic, first_hic, 1e-9 * first_hic) << "direction must not matter";
  }
}

TEST(HeadMetrics, Cfc1000BarelyTouchesA6msPulseAndResamplesNonUniformTime) {
  // CFC 1000 (-3 dB at 1650 Hz) passes a 6 ms half-sine (fundamental ~83 Hz): peak within 0.5 %.
  const double A = 150.0, T = 0.006, d[3] = {0, 0, 1};
  std::vector<double> t, xyz;
  half_sine_xyz(A, T, d, t, xyz);
  for (std::size_t i = 1; i + 1 < t.size(); i += 2) t[i] += 2e-7;  // jitter: non-uniform
  const HeadMetrics m = head_metrics_xyz(t, xyz, 1000, "jittered half-sine");
  EXPECT_TRUE(m.resampled);
  EXPECT_EQ(m.cfc, 1000);
  EXPECT_NEAR(m.peak_g, A, 0.005 * A);
}

TEST(HeadMetrics, BadInputIsRefused) {
  std::vector<double> t{0.0, 1e-5, 2e-5}, xyz(8, 0.0);
  EXPECT_THROW(head_metrics_xyz(t, xyz, 0, "short"), InputError);
  xyz.resize(9, 0.0);
  EXPECT_THROW(head_metrics_xyz(t, xyz, 500, "bad class"), InputError);
  EXPECT_THROW(head_metrics(t, {{0, 0, 0}, {0, 0, 0}}, 1.0, 0, "two channels"), InputError);
}

}  // namespace
}  // namespace crashlink::signal
