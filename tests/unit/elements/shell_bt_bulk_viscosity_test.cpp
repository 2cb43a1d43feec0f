// Membrane bulk viscosity of the Belytschko-Tsay shell (shell_bt_forces.cpp, its bulk viscosity
// phase): a rectangle a x b (the geometry x^{n+1}) under an imposed uniform in-plane velocity field
// v = L X, one step. The kernel takes the velocity strains on the mid-step geometry
// x - dt/2 v = (I - dt/2 L) X, where v is the gradient Lm = L (I - dt/2 L)^{-1}; tr below is
// tr Lm, and the work's area that of the mid-step geometry, det(I - dt/2 L) a b.
//   * compression (tr < 0): q = rho L_e (Q2 L_e tr^2 - Q1 c tr), L_e = A / diagonal,
//     c = sqrt(E / (rho (1 - nu^2))); the forces differ from those without viscosity by the
//     in-plane pressure q on the edges, Delta f_I = -q h A (B1_I, B2_I) (node 1 at the origin:
//     (q h b / 2, q h a / 2)), rotated with the element when it is tilted in space; the internal
//     energy by -q tr A h_mid dt; the step by the factor sqrt(1 + xi^2) - xi, xi = Q1 - Q2 L_e
//     tr / c; the stored stress is not changed by q. Tolerance 1e-10 relative (round-off).
//   * expansion, pure shear or the option off: no change at all (exact equality).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/vec3.h"
#include "solver/elements/shell_bt.h"

namespace {

namespace model = crashlink::model;
namespace materials = crashlink::materials;
namespace el = crashlink::elements;
using crashlink::Mat3;
using crashlink::Vec3;

constexpr double kE = 210e9, kNu = 0.3, kRho = 7850.0, kH = 0.002, kA = 0.04, kB = 0.025;
constexpr double kDt = 1e-7;  // [s]

/// The in-plane gradient on the mid-step geometry (the kernel's mid-step geometry): tr Lm and det(I
/// - dt/2 L).
struct MidStep {
  double tr = 0.0, area_factor = 1.0;
};
MidStep mid_step(const double (&L)[2][2]) {
  const double a = 0.5 * kDt;
  const double m00 = 1.0 - a * L[0][0], m01 = -a * L[0][1], m10 = -a * L[1][0],
               m11 = 1.0 - a * L[1][1];
  const double det = m00 * m11 - m01 * m10;  // M^{-1} = (m11, -m01; -m10, m00) / det
  return {(L[0][0] * m11 - L[0][1] * m10 - L[1][0] * m01 + L[1][1] * m00) / det, det};
}

struct StepRun {
  std::vector<double> f, m;
  el::KernelResult res;
  double h1 = 0.0, sxx = 0.0;
};

/// One step of dt on the rectangle [0, a] x [0, b] rotated by Q, velocity Q L X. `linear`:
/// StepInfo::linear_in_expansion.
StepRun run(const double (&Lg)[2][2], bool bulk, const Mat3& Q, bool linear = false) {
  model::Part part;
  part.name = "rect";
  part.kind = model::ElementKind::Shell4;
  part.thickness_m = kH;
  part.through_thickness_points = 3;
  part.connectivity = {0, 1, 2, 3};
  part.element_id = {7};
  const materials::Material mat{"steel", materials::MaterialKind::Elastic, kRho, kE, kNu, {}};
  const double X[4][2] = {{0, 0}, {kA, 0}, {kA, kB}, {0, kB}};
  std::vector<double> x(12), v(12), w(12, 0.0);
  StepRun r;
  r.f.assign(12, 0.0);
  r.m.assign(12, 0.0);
  for (std::size_t n = 0; n < 4; ++n) {
    const Vec3 xl{X[n][0], X[n][1], 0.0};
    const Vec3 vl{Lg[0][0] * X[n][0] + Lg[0][1] * X[n][1], Lg[1][0] * X[n][0] + Lg[1][1] * X[n][1],
                  0.0};
    const Vec3 xg = crashlink::mul(Q, xl), vg = crashlink::mul(Q, vl);
    for (std::size_t c = 0; c < 3; ++c) {
      x[3 * n + c] = xg[c];
      v[3 * n + c] = vg[c];
    }
  }
  el::ShellState st = el::make_shell_state(part);
  el::StepInfo step{kDt, bulk};
  step.linear_in_expansion = linear;
  r.res = el::shell_internal_forces(part, mat, st,
                                    {x.data(), v.data(), w.data(), r.f.data(), r.m.data()}, step);
  r.h1 = st.thickness_m[0];
  r.sxx = st.sigma(0, 1, 0);
  return r;
}

Mat3 tilt() {
  return crashlink::rotation_from_vector({0.4, -0.9, 0.3});
}

}  // namespace

TEST(ShellBtBulkViscosity, CompressionAddsTheInPlanePressure) {
  for (const Mat3& Q : {crashlink::identity3(), tilt()}) {
    const double Lg[2][2] = {{-800.0, 150.0}, {150.0, -300.0}};  // tr L = -1100 /s
    const StepRun on = run(Lg, true, Q), off = run(Lg, false, Q);
    const MidStep mid = mid_step(Lg);
    const double tr = mid.tr;
    const double c = std::sqrt(kE / (kRho * (1 - kNu * kNu)));
    const double Le = kA * kB / std::hypot(kA, kB);
    const double Q1 = 0.06, Q2 = 1.5;  // StepInfo defaults
    const double q = kRho * Le * (Q2 * Le * tr * tr - Q1 * c * tr);
    ASSERT_GT(q, 0.0);
    const double h1 = on.h1;
    EXPECT_EQ(on.h1, off.h1);    // q is not in the stress: same thickness strain
    EXPECT_EQ(on.sxx, off.sxx);  // nor in the stored stress
    // Delta f_I = -q h1 A (B1_I, B2_I); B1 = (-1, 1, 1, -1) / (2a), B2 = (-1, -1, 1, 1) / (2b).
    const double s1[4] = {-1, 1, 1, -1}, s2[4] = {-1, -1, 1, 1};
    const double fscale = q * h1 * std::max(kA, kB);
    for (std::size_t n = 0; n < 4; ++n) {
      const Vec3 dl{-q * h1 * kA * kB * s1[n] / (2 * kA), -q * h1 * kA * kB * s2[n] / (2 * kB),
                    0.0};
      const Vec3 dg = crashlink::mul(Q, dl);
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(on.f[3 * n + k] - off.f[3 * n + k], dg[k], 1e-10 * fscale) << "node " << n;
        EXPECT_NEAR(on.m[3 * n + k], off.m[3 * n + k], 1e-12 * fscale * kA);
      }
    }
    // Energy: trapezoid on the pressure, 1/2 (q^n + q) (-tr) A h_mid dt, with q^n = 0 on this
    // first step from rest.
    const double dW = -0.5 * q * tr * mid.area_factor * kA * kB * 0.5 * (kH + h1) * kDt;
    EXPECT_NEAR(on.res.internal_energy_increment_J - off.res.internal_energy_increment_J, dW,
                1e-10 * dW);
    // Step: (L_e / c) (sqrt(1 + xi^2) - xi).
    const double xi = Q1 - Q2 * Le * tr / c;
    EXPECT_NEAR(off.res.dt_stable_s, Le / c, 1e-12 * Le / c);
    EXPECT_NEAR(on.res.dt_stable_s, Le / c * (std::sqrt(1 + xi * xi) - xi), 1e-12 * Le / c);
    EXPECT_LT(on.res.dt_stable_s, off.res.dt_stable_s);
  }
}

TEST(ShellBtBulkViscosity, OffInExpansionAndShear) {
  const double expand[2][2] = {{800.0, 150.0}, {-50.0, 300.0}};
  const double shear[2][2] = {{0.0, 400.0}, {400.0, 0.0}};
  // (pure shear in the untilted frame, where tr D_m is exactly 0, not a round-off residue)
  for (const auto* Lg : {&expand, &shear}) {
    const Mat3 Q = Lg == &expand ? tilt() : crashlink::identity3();
    const StepRun on = run(*Lg, true, Q), off = run(*Lg, false, Q);
    for (std::size_t i = 0; i < 12; ++i) {
      EXPECT_EQ(on.f[i], off.f[i]);
      EXPECT_EQ(on.m[i], off.m[i]);
    }
    EXPECT_EQ(on.res.internal_energy_increment_J, off.res.internal_energy_increment_J);
    EXPECT_EQ(on.res.dt_stable_s, off.res.dt_stable_s);
  }
}

// Abaqus/Explicit's linear bulk viscosity (StepInfo::linear_in_expansion): in expansion the Q1
// term alone, q = -rho L_e Q1 c tr < 0 (a viscous tension), its work 1/2 (0 + q)(-tr) A h_mid dt
// > 0 dissipated, and xi = Q1 in the step; in compression the same q as without it.
TEST(ShellBtBulkViscosity, LinearTermInExpansionWhenAsked) {
  const double expand[2][2] = {{800.0, 150.0}, {-50.0, 300.0}};  // tr = 1100 /s
  const double compress[2][2] = {{-800.0, 150.0}, {150.0, -300.0}};
  const Mat3 Q = tilt();
  const StepRun on = run(expand, true, Q, true), off = run(expand, false, Q, true);
  const MidStep mid = mid_step(expand);
  const double tr = mid.tr;
  const double c = std::sqrt(kE / (kRho * (1 - kNu * kNu)));
  const double Le = kA * kB / std::hypot(kA, kB);
  const double Q1 = 0.06;
  const double q = -kRho * Le * Q1 * c * tr;
  const double h1 = on.h1;
  const double s1[4] = {-1, 1, 1, -1}, s2[4] = {-1, -1, 1, 1};
  const double fscale = std::abs(q) * h1 * std::max(kA, kB);
  for (std::size_t n = 0; n < 4; ++n) {
    const Vec3 dl{-q * h1 * kA * kB * s1[n] / (2 * kA), -q * h1 * kA * kB * s2[n] / (2 * kB), 0.0};
    const Vec3 dg = crashlink::mul(Q, dl);
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(on.f[3 * n + k] - off.f[3 * n + k], dg[k], 1e-10 * fscale) << "node " << n;
  }
  const double dW = -0.5 * q * tr * mid.area_factor * kA * kB * 0.5 * (kH + h1) * kDt;
  ASSERT_GT(dW, 0.0);
  EXPECT_NEAR(on.res.internal_energy_increment_J - off.res.internal_energy_increment_J, dW,
              1e-10 * dW);
  EXPECT_NEAR(on.res.dt_stable_s, Le / c * (std::sqrt(1 + Q1 * Q1) - Q1), 1e-12 * Le / c);
  // compression: the option changes nothing
  const StepRun a = run(compress, true, Q, true), b = run(compress, true, Q, false);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(a.f[i], b.f[i]);
  EXPECT_EQ(a.res.dt_stable_s, b.res.dt_stable_s);
}
