// The coordinator's side of the `paper` scheme (coupling/paper_coupling.h) against values
// computed by hand: two interface nodes, known partial masses, known free forces/accelerations.
//   [5]  M = sum_k m^k;   a^k = f^k / M
//   [8]  a* = a^A + a^B   (= (f^A + f^B) / M: the mono-domain acceleration)
//   [9], [10]  a*_A(t) = a_A(t) + a_B(t0) (t1 - t)/(t1 - t0) + a_B(t1) (t - t0)/(t1 - t0)
//   [11] da = (u_ref - u) / (dt^n dt^{n-1/2})
#include "coupling/paper_coupling.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "core/errors.h"

namespace crashlink::coupling::paper {
namespace {

// Node 0: partial masses 1.0 kg (A) and 3.0 kg (B); node 1: 2.5 kg in A and 0 in B (a copy of
// A's node held by B: no own mass).
const std::vector<std::vector<double>> kPartial = {{1.0, 2.5}, {3.0, 0.0}};

TEST(PaperCoupling, SummedMassIsTheSumOverDomains) {  // [5]
  const auto m = summed_mass(kPartial);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], 4.0);
  EXPECT_EQ(m[1], 2.5);
}

TEST(PaperCoupling, SummedMassRejectsBadInput) {
  const std::vector<std::vector<double>> unequal = {{1.0, 2.0}, {1.0}};
  EXPECT_THROW(summed_mass(unequal), ModelError);
  const std::vector<std::vector<double>> negative = {{1.0, -2.0}, {1.0, 3.0}};
  EXPECT_THROW(summed_mass(negative), ModelError);
  const std::vector<std::vector<double>> massless = {{1.0, 0.0}, {1.0, 0.0}};
  EXPECT_THROW(summed_mass(massless), ModelError);
  EXPECT_THROW(summed_mass({}), ModelError);
}

TEST(PaperCoupling, LinkAccelerationIsTheSumOfTheFreeAccelerations) {  // [5], [8]
  const auto m = summed_mass(kPartial);
  // Free forces of each domain on the two nodes [N], xyz.
  const std::array<double, 6> fA{8.0, -4.0, 2.0, 5.0, 0.0, -2.5};
  const std::array<double, 6> fB{-4.0, 12.0, 0.0, 0.0, 1.25, 0.0};
  std::array<double, 6> aA{}, aB{};
  for (std::size_t i = 0; i < 6; ++i) {
    aA[i] = fA[i] / m[i / 3];  // [5]: each domain divides by the SUMMED mass
    aB[i] = fB[i] / m[i / 3];
  }
  // By hand: node 0 M = 4: aA = (2, -1, 0.5), aB = (-1, 3, 0); node 1 M = 2.5: aA = (2, 0, -1),
  // aB = (0, 0.5, 0).
  EXPECT_EQ(aA[0], 2.0);
  EXPECT_EQ(aB[4], 0.5);
  std::array<double, 6> a{};
  const std::array<std::span<const double>, 2> both{aA, aB};
  link_acceleration(both, a);
  const std::array<double, 6> expected{1.0, 2.0, 0.5, 2.0, 0.5, -1.0};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(a[i], expected[i]) << i;
    // = the mono-domain acceleration (f^A + f^B) / M ([6]-[7]: the link makes one node of two)
    EXPECT_DOUBLE_EQ(a[i], (fA[i] + fB[i]) / m[i / 3]) << i;
  }
  // [8]: both domains receive the same bits, whatever the order they are listed in.
  std::array<double, 6> a2{};
  const std::array<std::span<const double>, 2> swapped{aB, aA};
  link_acceleration(swapped, a2);
  EXPECT_EQ(a, a2);
  std::array<double, 5> wrong{};
  EXPECT_THROW(link_acceleration(both, wrong), ModelError);
}

TEST(PaperCoupling, InterpolationWeightOfTen) {  // [10]
  const Weight w = interpolation_weight(3, 0, 4);
  EXPECT_EQ(w.num, 3);
  EXPECT_EQ(w.den, 4);
  EXPECT_EQ(w.lower_factor(), 0.25);                // (t1 - t) / (t1 - t0)
  EXPECT_EQ(w.upper_factor(), 0.75);                // (t - t0) / (t1 - t0)
  const Weight at = interpolation_weight(7, 7, 7);  // coinciding instants: no interpolation
  EXPECT_EQ(at.num, 0);
  EXPECT_EQ(at.den, 1);
  EXPECT_EQ(interpolation_weight(10, 10, 30).num, 0);
  EXPECT_EQ(interpolation_weight(30, 10, 30).num, 20);
  EXPECT_THROW(interpolation_weight(31, 10, 30), ModelError);
  EXPECT_THROW(interpolation_weight(9, 10, 30), ModelError);
  EXPECT_THROW(interpolation_weight(10, 10, 5), ModelError);
}

TEST(PaperCoupling, MultiscaleAccelerationInterpolatesThePartner) {  // [9], [10]
  // Fine domain A at t = 3 inside the coarse domain B's step [0, 4] (ticks).
  const std::array<double, 6> a_own{1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  const std::array<double, 6> b0{4.0, 8.0, -4.0, 0.0, 0.0, 0.0};  // a_B(t_B^n = 0)
  const std::array<double, 6> b1{8.0, 0.0, 4.0, 4.0, -4.0, 0.0};  // a_B(t_B^{n+1} = 4)
  std::array<double, 6> out{};
  multiscale_acceleration(a_own, b0, b1, interpolation_weight(3, 0, 4), out);
  // a_B(3) = b0 / 4 + 3 b1 / 4 = (7, 2, 2, 3, -3, 0); plus a_own:
  const std::array<double, 6> expected{8.0, 2.0, 2.0, 3.0, -3.0, 1.0};
  EXPECT_EQ(out, expected);
  // At a coarse instant the states coincide: exactly [8], a_own + a_B, bit for bit.
  std::array<double, 6> at0{}, at4{}, link0{}, link4{};
  multiscale_acceleration(a_own, b0, b1, interpolation_weight(0, 0, 4), at0);
  multiscale_acceleration(a_own, b0, b1, interpolation_weight(4, 0, 4), at4);
  const std::array<std::span<const double>, 2> p0{a_own, b0}, p4{a_own, b1};
  link_acceleration(p0, link0);
  link_acceleration(p4, link4);
  EXPECT_EQ(at0, link0);
  EXPECT_EQ(at4, link4);
}

TEST(PaperCoupling, DriftCorrectionOfEleven) {     // [11]
  EXPECT_EQ(drift_step_product(0.5, 0.5), 0.25);   // dt^n dt^{n-1/2} at a constant step
  EXPECT_EQ(drift_step_product(0.5, 0.0), 0.125);  // first cycle: dt^{-1/2} = dt^0 / 2
  EXPECT_EQ(drift_step_product(1.0, 0.5), 0.75);   // variable step: 1 x (0.5 + 1) / 2
  EXPECT_THROW(drift_step_product(0.0, 0.5), ModelError);
  EXPECT_THROW(drift_step_product(0.5, -1.0), ModelError);
  // Node 0 lags its reference by (1, -2, 0) mm, node 1 is on it.
  const std::array<double, 6> u_ref{3e-3, -1e-3, 5e-3, 1.0, 2.0, 3.0};
  const std::array<double, 6> u{2e-3, 1e-3, 5e-3, 1.0, 2.0, 3.0};
  std::array<double, 6> da{};
  drift_correction(u_ref, u, 0.25, Drift::on, da);
  EXPECT_DOUBLE_EQ(da[0], 4e-3);  // 1e-3 / 0.25
  EXPECT_DOUBLE_EQ(da[1], -8e-3);
  EXPECT_EQ(da[2], 0.0);
  for (std::size_t i = 3; i < 6; ++i) EXPECT_EQ(da[i], 0.0);
  // The one-sided spring: stiffness M / (dt^n dt^{n-1/2}); 4 kg at dt = 0.5 s: 16 N/m.
  EXPECT_EQ(drift_stiffness(4.0, 0.25), 16.0);
  // Off: no correction.
  drift_correction(u_ref, u, 0.25, Drift::off, da);
  for (double x : da) EXPECT_EQ(x, 0.0);
  // add_drift: a* + da
  const std::array<double, 6> a_link{1.0, 2.0, 0.5, 2.0, 0.5, -1.0};
  const std::array<double, 6> d{0.5, -0.25, 0.0, 0.0, 0.0, 1.0};
  std::array<double, 6> out{};
  add_drift(a_link, d, out);
  EXPECT_EQ(out, (std::array<double, 6>{1.5, 1.75, 0.5, 2.0, 0.5, 0.0}));
  std::array<double, 3> short_da{};
  EXPECT_THROW(drift_correction(u_ref, u, 0.25, Drift::on, short_da), ModelError);
}

// [11] alone, integrated by central differences [2] against a fixed reference u_ref = 0: the
// correction moves the node onto u_ref in the first (half) step, then the one-sided spring
// oscillates with a period of exactly 6 steps (coupling-study/README.md finding 2).
TEST(PaperCoupling, DriftSpringClosesTheGapThenHasPeriodSix) {
  const double h = 0.5;
  const std::array<double, 3> zero{};
  std::array<double, 3> u{1.0, -2.0, 0.0}, v{}, da{};
  std::vector<double> ux;
  for (int n = 0; n < 14; ++n) {
    drift_correction(zero, u, drift_step_product(h, n == 0 ? 0.0 : h), Drift::on, da);
    const double dt_mid = n == 0 ? 0.5 * h : h;
    for (std::size_t i = 0; i < 3; ++i) {
      v[i] += dt_mid * da[i];  // [2]
      u[i] += h * v[i];
    }
    ux.push_back(u[0]);
    if (n == 0) {
      EXPECT_EQ(u, zero) << "one step onto the reference";
    }
  }
  const std::vector<double> expected{0.0,  -1.0, -1.0, 0.0, 1.0, 1.0, 0.0,
                                     -1.0, -1.0, 0.0,  1.0, 1.0, 0.0, -1.0};
  EXPECT_EQ(ux, expected);
}

}  // namespace
}  // namespace crashlink::coupling::paper
