// J2 hexahedron under uniaxial stress, driven through the kernel: the x stretch is prescribed,
// the lateral stretch (y = z by symmetry) is found each step by a secant iteration on the kernel
// (on a copy of the history) so that sigma_yy = sigma_zz = 0: lateral faces traction-free.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"

namespace {

namespace el = crashlink::elements;
using crashlink::elements::hex8::kPhi;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

}  // namespace

// sigma_xx follows sigma_y(eps_p) of the input curve within 1% (the return is exact on the curve,
// so the residual is the secant tolerance on the lateral stress), and eps_p matches the axial
// log strain minus the elastic strain, ln(lambda_x) - sigma_xx / E, within 1% once eps_p > 0.01
// (the midpoint integral of D_xx is the log strain to O(d eps^2)).
TEST(Hex8J2, UniaxialStressFollowsHardeningCurve) {
  const Material mat{
      "j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.05, 0.2}, {250e6, 350e6, 400e6}}};
  crashlink::model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  std::vector<double> X(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) X[3 * I + i] = 0.5 * (kPhi[i][I] + 1.0);
  auto config = [&](double lx, double lt) {
    std::vector<double> x(24);
    for (int I = 0; I < 8; ++I) {
      x[3 * I] = lx * X[3 * I];
      x[3 * I + 1] = lt * X[3 * I + 1];
      x[3 * I + 2] = lt * X[3 * I + 2];
    }
    return x;
  };
  el::StepInfo step;
  step.bulk_viscosity = false;
  auto st = el::make_hex8_state(part);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  el::hex8_internal_forces(part, mat, st, {X.data(), v.data(), nullptr, f.data(), nullptr}, step);

  const double dt = 1e-6, eps_end = 0.3;
  const int steps = 3000;
  step.dt_s = dt;
  double lt = 1.0;
  std::vector<double> xn = X;
  int checked = 0;
  for (int s = 1; s <= steps; ++s) {
    const double lx = std::exp(eps_end * s / steps);
    // sigma_yy after the step with lateral stretch t, from a copy of the history
    auto trial = [&](double t, el::Hex8State& h) {
      const auto x1 = config(lx, t);
      for (int k = 0; k < 24; ++k) v[k] = (x1[k] - xn[k]) / dt;
      std::fill(f.begin(), f.end(), 0.0);
      el::hex8_internal_forces(part, mat, h, {x1.data(), v.data(), nullptr, f.data(), nullptr},
                               step);
      return h.stress[1];
    };
    double t0 = lt, t1 = lt * (1.0 - 0.3 * eps_end / steps);
    auto h0 = st;
    double r0 = trial(t0, h0);
    for (int it = 0; it < 50; ++it) {
      auto h1 = st;
      const double r1 = trial(t1, h1);
      if (std::abs(r1) < 1e-6 * 250e6 || r1 == r0) {
        t0 = t1;
        break;
      }
      const double t2 = t1 - r1 * (t1 - t0) / (r1 - r0);
      t0 = t1;
      r0 = r1;
      t1 = t2;
    }
    lt = t0;
    trial(lt, st);  // commit
    xn = config(lx, lt);
    const double sxx = st.stress[0], ep = st.eps_p[0];
    EXPECT_NEAR(st.stress[1], 0.0, 1e-5 * 250e6);
    EXPECT_NEAR(st.stress[2], 0.0, 1e-5 * 250e6);
    if (ep > 0.0) {
      EXPECT_NEAR(sxx, mat.hardening.yield(ep), 0.01 * mat.hardening.yield(ep)) << "step " << s;
    }
    if (ep > 0.01) {
      EXPECT_NEAR(ep, std::log(lx) - sxx / 210e9, 0.01 * ep) << "step " << s;
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
  EXPECT_NEAR(st.eps_p[0], 0.3 - 400e6 / 210e9 - 0.0, 0.01 * 0.3);
}
