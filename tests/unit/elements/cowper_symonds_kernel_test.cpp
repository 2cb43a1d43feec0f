// Cowper-Symonds rate scaling through the element kernels (materials/cowper_symonds.h):
//   * hexahedron under uniaxial stress at a constant log strain rate (the lateral stretch found
//     by a secant so that sigma_yy = sigma_zz = 0, as hex8_j2_uniaxial_test): sigma_xx follows
//     the analytic sigma_y(eps_p) (1 + (rate / C)^(1/P)) at 100 and 1000 1/s;
//   * Belytschko-Tsay shell in a homogeneous membrane stretch at a constant rate: the rate
//     material's stresses equal those of a rate-free material whose curve is scaled by the
//     factor of that rate (the kernel computes each point's rate and scales its curve).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"
#include "solver/materials/cowper_symonds.h"
#include "tests/unit/elements/hex8_uniaxial_driver.h"

namespace {

namespace el = crashlink::elements;
namespace mt = crashlink::materials;

// Mild steel (N. Jones, Structural Impact, table 8.1: C = 40.4 1/s, P = 5).
constexpr double kC = 40.4, kP = 5.0;

mt::Material rate_steel(bool rate) {
  mt::Material m{"j2",   mt::MaterialKind::J2Plastic,
                 7850.0, 210e9,
                 0.3,    {{0.0, 0.05, 0.2}, {250e6, 350e6, 400e6}}};
  if (rate) {
    m.rate_c_per_s = kC;
    m.rate_p = kP;
  }
  return m;
}

/// Uniaxial stress at the log strain rate `rate` [1/s] to a log strain of 0.1; returns how many
/// plastic steps were compared with the analytic stress.
int hex_uniaxial(double rate) {
  const mt::Material mat = rate_steel(true);
  const double eps_end = 0.1;
  const int steps = 2000;
  const double phi = mt::cowper_symonds_factor(rate, kC, kP);
  int checked = 0;
  crashlink::testing::drive_hex8_uniaxial(
      mat, eps_end, steps, eps_end / (rate * steps), 1e-7 * 250e6,
      [&](int s, double, const el::Hex8State& st) {
        // Once the flow is plastic the lateral rate is -rate/2 up to the elastic part (the
        // curve's slope over E, under 0.1 %): the effective rate is the axial one.
        const double ep = st.eps_p[0];
        if (ep > 0.005) {
          const double expected = phi * mat.hardening.yield(ep);
          EXPECT_NEAR(st.stress[0], expected, 2e-3 * expected) << "rate " << rate << " step " << s;
          ++checked;
        }
      });
  return checked;
}

}  // namespace

TEST(CowperSymondsKernel, HexUniaxialStressFollowsTheScaledCurve) {
  // factor 2.198 at 100 1/s, 2.899 at 1000 1/s
  EXPECT_GT(hex_uniaxial(100.0), 1500);
  EXPECT_GT(hex_uniaxial(1000.0), 1500);
}

TEST(CowperSymondsKernel, ShellMembraneStretchEqualsTheScaledCurve) {
  // One flat 10 x 10 mm shell, 5 points, stretched in its plane at constant true rates
  // (a, b) = (500, -100) 1/s: v = (a x, b y, 0) at the current positions; a second one beside it
  // at rest, so that the kernel's packed return (the yielding points of a batch only) runs.
  crashlink::model::Part part;
  part.name = "one";
  part.kind = crashlink::model::ElementKind::Shell4;
  part.thickness_m = 0.001;
  part.through_thickness_points = 5;
  part.hourglass_coefficient = 0.1;
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1, 2};
  const double a = 500.0, b = -100.0, dt = 1e-7;
  // x^{n+1} = exp(a dt) x^n, v^{n+1/2} = (x^{n+1} - x^n) / dt; the kernel's rate on the mid-step
  // geometry is then (2 / dt) tanh(a dt / 2).
  const double ra = 2.0 / dt * std::tanh(0.5 * a * dt), rb = 2.0 / dt * std::tanh(0.5 * b * dt);
  const double rate = mt::plane_effective_strain_rate(ra, rb, 0.0);
  const double phi = mt::cowper_symonds_factor(rate, kC, kP);
  mt::Material with_rate = rate_steel(true), scaled = rate_steel(false);
  for (double& y : scaled.hardening.sigma_y_Pa) y *= phi;
  std::vector<double> x = {0, 0, 0, 0.01, 0, 0, 0.01, 0.01, 0, 0,   0.01, 0,
                           1, 0, 0, 1.01, 0, 0, 1.01, 0.01, 0, 1.0, 0.01, 0};
  el::ShellState s1 = el::make_shell_state(part), s2 = el::make_shell_state(part);
  double worst = 0.0;
  for (int it = 0; it < 3000; ++it) {  // to 0.15 log strain in x
    std::vector<double> v(24, 0.0), w(24, 0.0), f1(24, 0.0), m1(24, 0.0), f2(24, 0.0), m2(24, 0.0);
    if (it > 0)
      for (int n = 0; n < 4; ++n) {
        v[3 * n] = (std::exp(a * dt) - 1.0) / dt * x[3 * n];
        v[3 * n + 1] = (std::exp(b * dt) - 1.0) / dt * x[3 * n + 1];
        x[3 * n] *= std::exp(a * dt);
        x[3 * n + 1] *= std::exp(b * dt);
      }
    const el::StepInfo step{it == 0 ? 0.0 : dt, false};
    el::shell_internal_forces(part, with_rate, s1,
                              {x.data(), v.data(), w.data(), f1.data(), m1.data()}, step);
    el::shell_internal_forces(part, scaled, s2,
                              {x.data(), v.data(), w.data(), f2.data(), m2.data()}, step);
    for (std::size_t k = 0; k < s1.sigma_Pa.size(); ++k)
      worst = std::max(worst, std::abs(s1.sigma_Pa[k] - s2.sigma_Pa[k]) / (phi * 250e6));
  }
  ASSERT_FALSE(s1.eps_p.empty());
  EXPECT_GT(s1.eps_p[0], 0.1);
  // the two returns differ only in where phi multiplies (the curve's points or its segment) and
  // in the Newton iterates (tolerance 1e-12 of sigma_y)
  EXPECT_LT(worst, 1e-10);
  std::printf(
      "[measured] shell membrane (%.0f, %.0f) 1/s: effective rate %.1f 1/s, factor %.4f, "
      "eps_p %.4f, largest stress difference %.1e of phi sigma_y0\n",
      a, b, rate, phi, s1.eps_p[0], worst);
}

// Bending: each Gauss point's rate is proportional to |zeta| (rate = |zeta| h/2 kappa_dot), so
// at convergence of the return vm_k / sigma_y(eps_p,k) - 1 = (|zeta_k| R / C)^(1/P) for some R
// common to the points, and the ratio of that between the outer and the inner points is
// (zeta_outer / zeta_inner)^(1/P), whatever the curvature rate: each point's own rate scales its
// own curve (the per-point factors are not swapped or shared).
TEST(CowperSymondsKernel, ShellBendingScalesEachPointByItsOwnRate) {
  crashlink::model::Part part;
  part.name = "one";
  part.kind = crashlink::model::ElementKind::Shell4;
  part.thickness_m = 0.001;
  part.through_thickness_points = 5;
  part.hourglass_coefficient = 0.1;
  part.connectivity = {0, 1, 2, 3};
  part.element_id = {1};
  const mt::Material mat = rate_steel(true);
  const std::vector<double> x = {0, 0, 0, 0.01, 0, 0, 0.01, 0.01, 0, 0, 0.01, 0};
  // omega_y = a x: a curvature rate a [1/(m s)]; outer points (zeta 0.906, h/2 0.5 mm) at
  // 0.906 x 0.5e-3 x 1e6 = 453 1/s
  const double a = 1e6, dt = 1e-8;
  el::ShellState st = el::make_shell_state(part);
  for (int it = 0; it < 4000; ++it) {  // to a surface strain of 0.018, 0.011 inside
    std::vector<double> v(12, 0.0), w(12, 0.0), f(12, 0.0), m(12, 0.0);
    for (int n = 0; n < 4; ++n) w[3 * n + 1] = a * x[3 * n];
    el::shell_internal_forces(part, mat, st, {x.data(), v.data(), w.data(), f.data(), m.data()},
                              el::StepInfo{it == 0 ? 0.0 : dt, false});
  }
  auto excess = [&](int k) {  // vm / sigma_y(eps_p) - 1 at point k
    const double sx = st.sigma(0, k, 0), sy = st.sigma(1, k, 0), sxy = st.sigma(2, k, 0);
    const double vm = std::sqrt(sx * sx + sy * sy - sx * sy + 3.0 * sxy * sxy);
    return vm / mat.hardening.yield(st.plastic_strain(k, 0)) - 1.0;
  };
  // points 0..4 at zeta -0.906, -0.538, 0, 0.538, 0.906 (Gauss-Legendre)
  ASSERT_GT(st.plastic_strain(1, 0), 0.0);
  ASSERT_GT(st.plastic_strain(3, 0), 0.0);
  const double expected = std::pow(st.zeta[4] / st.zeta[3], 1.0 / kP);
  std::printf(
      "[measured] shell bending: factor - 1 at the outer/inner points %.6f, %.6f (top), %.6f, "
      "%.6f (bottom); outer/inner %.9f, (zeta_o/zeta_i)^(1/P) = %.9f\n",
      excess(4), excess(3), excess(0), excess(1), excess(4) / excess(3), expected);
  EXPECT_NEAR(excess(4) / excess(3), expected, 1e-6 * expected);
  EXPECT_NEAR(excess(0) / excess(1), expected, 1e-6 * expected);
  EXPECT_GT(excess(3), 0.5);  // the rate effect is there (factor 1.5 and more)
}
