// Flanagan-Belytschko hourglass control (stiffness form): restoring forces of an hourglass motion
// are orthogonal to the rigid-body and linear modes (zero net force, zero moment, zero work in any
// linear field), have the stiffness k = kappa (lambda + 2 mu) b.b / (8 V) on a cube, and store
// energy without dissipation (a closed hourglass cycle returns the energy).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"

namespace {

namespace el = crashlink::elements;
using crashlink::elements::hex8::kPhi;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

const Material kSteel{"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};

crashlink::model::Part one_hex() {
  crashlink::model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  part.hourglass_coefficient = 0.1;
  return part;
}

std::vector<double> hex(double distortion, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-distortion, distortion);
  std::vector<double> x(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) x[3 * I + i] = 0.5 * (kPhi[i][I] + 1.0) + u(gen);
  return x;
}

// Hourglass part of the force: total minus b_iI sigma_ij (stress part, FB eq. 13), no viscosity.
std::vector<double> hourglass_part(const std::vector<double>& x, const el::Hex8State& st,
                                   const std::vector<double>& f) {
  double xl[3][8][1], b[3][8][1], gx[4][3][1], vol[1];
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) xl[i][I][0] = x[3 * I + i];
  el::hex8::volume_gradient<1>(xl, b, gx, vol);
  const double* s = st.stress.data();
  const double S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  std::vector<double> fh = f;
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) fh[3 * I + i] -= S[i][j] * b[j][I][0];
  return fh;
}

}  // namespace

// Each hourglass mode Gamma_alpha in each direction on a distorted hex: the hourglass forces have
// zero resultant, zero moment and do no work in any linear field (sum_I f_iI x_jI = 0). Tolerance
// 1e-10 of the largest hourglass force component (round-off of the sums over 8 nodes).
TEST(Hex8Hourglass, ForcesOrthogonalToRigidAndLinearModes) {
  const auto part = one_hex();
  el::StepInfo step;
  step.bulk_viscosity = false;
  for (int al = 0; al < 4; ++al)
    for (int dir = 0; dir < 3; ++dir) {
      const auto x0 = hex(0.2, 5);
      auto st = el::make_hex8_state(part);
      std::vector<double> v(24, 0.0), f(24, 0.0);
      step.dt_s = 0.0;
      el::hex8_internal_forces(part, kSteel, st, {x0.data(), v.data(), nullptr, f.data(), nullptr},
                               step);
      for (int I = 0; I < 8; ++I) v[3 * I + dir] = 1e-3 * kPhi[3 + al][I];
      step.dt_s = 1e-6;
      std::vector<double> x = x0;
      for (int k = 0; k < 24; ++k) x[k] += step.dt_s * v[k];
      std::fill(f.begin(), f.end(), 0.0);
      el::hex8_internal_forces(part, kSteel, st, {x.data(), v.data(), nullptr, f.data(), nullptr},
                               step);
      const auto fh = hourglass_part(x, st, f);
      double fmax = 0.0;
      for (double fi : fh) fmax = std::max(fmax, std::abs(fi));
      ASSERT_GT(fmax, 0.0) << "mode " << al << " dir " << dir;
      for (int i = 0; i < 3; ++i) {
        double net = 0.0;
        for (int I = 0; I < 8; ++I) net += fh[3 * I + i];
        EXPECT_NEAR(net, 0.0, 1e-10 * fmax);
        for (int j = 0; j < 3; ++j) {
          double lin = 0.0;  // work in the linear field u_i = x_j; the moment is its skew part
          for (int I = 0; I < 8; ++I) lin += fh[3 * I + i] * x[3 * I + j];
          EXPECT_NEAR(lin, 0.0, 1e-10 * fmax) << "i " << i << " j " << j;
        }
      }
    }
}

// Unit cube, one step of the xi-eta mode in x: gamma = Gamma (cube), qdot = Gamma.v = 8 v0,
// f_I = k dt qdot Gamma_I with k = kappa (lambda + 2 mu) b.b / (8 V), b.b = 24/16 V^2 / h^2.
// Exact up to the change of gamma and b over the step, O(u/h) = 1e-9 (tolerance 1e-8 relative).
// Then a closed cycle (out and back) returns the hourglass energy to zero: the stiffness form is
// elastic (1e-9 of the peak energy).
TEST(Hex8Hourglass, CubeStiffnessAndEnergyIsConserved) {
  const auto part = one_hex();
  el::StepInfo step;
  step.bulk_viscosity = false;
  const auto x0 = hex(0.0, 1);
  auto st = el::make_hex8_state(part);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  el::hex8_internal_forces(part, kSteel, st, {x0.data(), v.data(), nullptr, f.data(), nullptr},
                           step);
  const double v0 = 1e-3, dt = 1e-6;
  for (int I = 0; I < 8; ++I) v[3 * I] = v0 * kPhi[5][I];
  std::vector<double> x = x0;
  step.dt_s = dt;
  double e_hg = 0.0, e_peak = 0.0;
  const int n = 50;
  for (int s = 0; s < 2 * n; ++s) {
    const double sign = s < n ? 1.0 : -1.0;
    for (int I = 0; I < 8; ++I) v[3 * I] = sign * v0 * kPhi[5][I];
    for (int k = 0; k < 24; ++k) x[k] += dt * v[k];
    std::fill(f.begin(), f.end(), 0.0);
    e_hg += el::hex8_internal_forces(part, kSteel, st,
                                     {x.data(), v.data(), nullptr, f.data(), nullptr}, step)
                .hourglass_energy_increment_J;
    e_peak = std::max(e_peak, e_hg);
    if (s == 0) {
      const double lambda = kSteel.lame_lambda_Pa(), mu = kSteel.shear_modulus_Pa();
      const double k = 0.1 * (lambda + 2 * mu) * 1.5 / 8.0;  // V = h = 1
      for (int I = 0; I < 8; ++I)
        EXPECT_NEAR(f[3 * I], k * dt * 8 * v0 * kPhi[5][I], 1e-8 * k * dt * 8 * v0);
    }
  }
  EXPECT_GT(e_peak, 0.0);
  EXPECT_NEAR(e_hg, 0.0, 1e-9 * e_peak);
}
