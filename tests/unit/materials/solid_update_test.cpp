// Solid material updates (solid_update.h): hypoelastic increment and J2 radial return with
// piecewise-linear hardening.
#include "solver/materials/solid_update.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using crashlink::materials::HardeningCurve;
using crashlink::materials::hypoelastic_increment;
using crashlink::materials::j2_radial_return;
using crashlink::materials::Voigt6;
using crashlink::materials::von_mises;

namespace {
constexpr double kE = 210e9, kNu = 0.3;
const double kMu = kE / (2 * (1 + kNu)), kLambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
}  // namespace

// Uniaxial strain rate: sigma_xx = (lambda + 2 mu) d dt, sigma_yy = lambda d dt; shear 2 mu.
// Exact arithmetic (1e-12 relative).
TEST(SolidElastic, HypoelasticIncrement) {
  Voigt6 s{};
  hypoelastic_increment(kLambda, kMu, {1.0, 0.0, 0.0, 0.5, 0.0, 0.0}, 1e-3, s);
  EXPECT_NEAR(s[0], (kLambda + 2 * kMu) * 1e-3, 1e-12 * kE);
  EXPECT_NEAR(s[1], kLambda * 1e-3, 1e-12 * kE);
  EXPECT_NEAR(s[3], 2 * kMu * 0.5e-3, 1e-12 * kE);
  EXPECT_DOUBLE_EQ(von_mises({100.0, 0, 0, 0, 0, 0}), 100.0);
  EXPECT_NEAR(von_mises({0, 0, 0, 100.0, 0, 0}), 100.0 * std::sqrt(3.0), 1e-12);
}

// Random trial stresses far beyond yield, on a three-segment curve with extrapolation: after the
// return vm = sigma_y(ep_n + d_ep) to 1e-10 relative (consistency), the pressure is unchanged and
// the deviator is scaled, not turned (normality of the radial return), and d_ep = (q_tr - vm)/3mu
// (the flow rule); all round-off level (1e-10 relative).
TEST(SolidJ2, RadialReturnIsConsistentAcrossSegments) {
  const HardeningCurve h{{0.0, 0.002, 0.05, 0.2}, {250e6, 300e6, 350e6, 400e6}};
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int plastic = 0;
  for (int t = 0; t < 2000; ++t) {
    Voigt6 s;
    const double amp = 2e9 * std::abs(u(gen)) + 1e6;
    for (double& c : s) c = amp * u(gen);
    const double ep_n = 0.25 * std::abs(u(gen)) * (t % 3 == 0 ? 0.01 : 1.0);
    const Voigt6 tr = s;
    const double q_tr = von_mises(tr), p_tr = (tr[0] + tr[1] + tr[2]) / 3;
    const auto r = j2_radial_return(h, kMu, ep_n, s);
    const double y = h.yield(ep_n + r.delta_eps_p);
    if (r.delta_eps_p == 0.0) {
      EXPECT_LE(q_tr, h.yield(ep_n));
      continue;
    }
    ++plastic;
    EXPECT_NEAR(von_mises(s), y, 1e-10 * y);
    EXPECT_NEAR(r.yield_Pa, y, 1e-10 * y);
    EXPECT_NEAR((s[0] + s[1] + s[2]) / 3, p_tr, 1e-10 * amp);
    EXPECT_NEAR(r.delta_eps_p, (q_tr - von_mises(s)) / (3 * kMu), 1e-10 * r.delta_eps_p + 1e-18);
    const double scale = von_mises(s) / q_tr;
    for (int k = 3; k < 6; ++k) EXPECT_NEAR(s[k], scale * tr[k], 1e-10 * amp);
    EXPECT_NEAR(s[0] - s[1], scale * (tr[0] - tr[1]), 1e-10 * amp);
  }
  EXPECT_GT(plastic, 1000);
}

// Linear hardening H: the closed form d_ep = (q_tr - sigma_y) / (3 mu + H) (Simo-Hughes Box 3.1)
// and perfect plasticity (one-point curve): round-off (1e-12 relative).
TEST(SolidJ2, ClosedFormOnOneSegmentAndPerfectPlasticity) {
  const double H = 2e9;
  const HardeningCurve lin{{0.0, 1.0}, {300e6, 300e6 + H}};
  Voigt6 s{600e6, 0, 0, 0, 0, 0};
  const auto r = j2_radial_return(lin, kMu, 0.0, s);
  EXPECT_NEAR(r.delta_eps_p, (600e6 - 300e6) / (3 * kMu + H), 1e-12);
  const HardeningCurve perfect{{0.0}, {300e6}};
  Voigt6 t{0, 0, 0, 400e6, 0, 0};
  const auto rp = j2_radial_return(perfect, kMu, 0.3, t);
  EXPECT_NEAR(von_mises(t), 300e6, 1e-12 * 300e6);
  EXPECT_NEAR(rp.delta_eps_p, (400e6 * std::sqrt(3.0) - 300e6) / (3 * kMu), 1e-12);
}

// The closed form on the starting segment (j2_segment: d_ep = (q_tr - sigma_y) / (3 mu + H), used
// lane-wise by the batched kernels) is the segment walk of j2_radial_return whenever it ends on
// that segment (ep_n + d_ep <= end): round-off (1e-12 relative). The lower bound of the curve is
// its smallest point, 0 when the last segment softens.
TEST(SolidJ2, SegmentClosedFormEqualsWalkOnItsSegment) {
  using crashlink::materials::j2_segment;
  using crashlink::materials::j2_yield_lower_bound;
  const HardeningCurve h{{0.0, 0.002, 0.05, 0.2}, {250e6, 300e6, 350e6, 400e6}};
  std::mt19937 gen(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int closed = 0;
  for (int t = 0; t < 2000; ++t) {
    Voigt6 s;
    const double amp = 4e8 * std::abs(u(gen)) + 1e6;
    for (double& c : s) c = amp * u(gen);
    const double ep_n = t % 4 == 0 ? 0.002 : 0.25 * std::abs(u(gen));  // a kink, or anywhere
    const auto seg = j2_segment(h, ep_n);
    EXPECT_DOUBLE_EQ(seg.yield_Pa, h.yield(ep_n));
    EXPECT_DOUBLE_EQ(seg.slope_Pa, h.slope(ep_n));
    const double q_tr = von_mises(s);
    const Voigt6 tr = s;
    const auto r = j2_radial_return(h, kMu, ep_n, s);
    if (!(q_tr > seg.yield_Pa)) continue;
    const double d = (q_tr - seg.yield_Pa) / (3 * kMu + seg.slope_Pa);
    if (!(ep_n + d <= seg.end)) continue;
    ++closed;
    EXPECT_NEAR(r.delta_eps_p, d, 1e-12 * d);
    const double scale = 1.0 - 3 * kMu * d / q_tr;
    EXPECT_NEAR(s[3], scale * tr[3], 1e-12 * amp);
  }
  EXPECT_GT(closed, 500);
  EXPECT_EQ(j2_segment(h, 1.0).end, std::numeric_limits<double>::infinity());
  EXPECT_EQ(j2_segment(h, 0.01).end, 0.05);
  EXPECT_EQ(j2_yield_lower_bound(h), 250e6);
  EXPECT_EQ(j2_yield_lower_bound(HardeningCurve{{0.0, 0.1}, {300e6, 200e6}}), 0.0);
  EXPECT_EQ(j2_yield_lower_bound(HardeningCurve{{0.0}, {300e6}}), 300e6);
}
