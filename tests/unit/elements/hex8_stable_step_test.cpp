// Stable step of one free one-point hexahedron against its exact highest frequency: stiffness K
// by finite differences of the force kernel itself (one-point + hourglass stiffness), lumped mass
// from hex8_lumped_mass, omega_max^2 = largest eigenvalue of M^{-1/2} K M^{-1/2} (Eigen).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"

namespace {

namespace el = crashlink::elements;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

constexpr double kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                 kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

std::vector<double> hex(double h, double distortion, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-distortion, distortion);
  std::vector<double> x(24);
  for (int I = 0; I < 8; ++I) {
    x[3 * I] = 0.5 * h * (kXi[I] + 1) + h * u(gen);
    x[3 * I + 1] = 0.5 * h * (kEta[I] + 1) + h * u(gen);
    x[3 * I + 2] = 0.5 * h * (kZeta[I] + 1) + h * u(gen);
  }
  return x;
}

struct Check {
  double dt_kernel, dt_exact;
};

Check stable_step(const std::vector<double>& x0, const Material& mat, double hg) {
  crashlink::model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  part.hourglass_coefficient = hg;
  el::StepInfo step;
  step.bulk_viscosity = false;  // the bound without damping; viscosity only shortens it
  std::vector<double> v(24, 0.0), f(24, 0.0);
  auto st0 = el::make_hex8_state(part);
  const auto r0 = el::hex8_internal_forces(part, mat, st0,
                                           {x0.data(), v.data(), nullptr, f.data(), nullptr}, step);

  // K column j = f(u = tau e_j) / tau, tau = 1e-9 of the size: linearisation error ~1e-9 relative
  double h = 0.0;
  for (int k = 0; k < 24; ++k) h = std::max(h, std::abs(x0[k]));
  const double dt = 1e-9, vel = h;  // u = dt * vel = 1e-9 h
  Eigen::MatrixXd K(24, 24);
  for (int j = 0; j < 24; ++j) {
    auto st = el::make_hex8_state(part);
    std::fill(v.begin(), v.end(), 0.0);
    std::fill(f.begin(), f.end(), 0.0);
    el::hex8_internal_forces(part, mat, st, {x0.data(), v.data(), nullptr, f.data(), nullptr},
                             step);
    v[j] = vel;
    std::vector<double> x = x0;
    x[j] += dt * vel;
    std::fill(f.begin(), f.end(), 0.0);
    step.dt_s = dt;
    el::hex8_internal_forces(part, mat, st, {x.data(), v.data(), nullptr, f.data(), nullptr}, step);
    step.dt_s = 0.0;
    for (int i = 0; i < 24; ++i) K(i, j) = f[i] / (dt * vel);
  }
  std::vector<double> m(8, 0.0);
  el::hex8_lumped_mass(part, mat, x0.data(), m.data());
  Eigen::MatrixXd A = 0.5 * (K + K.transpose());
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j) A(i, j) /= std::sqrt(m[i / 3] * m[j / 3]);
  const double w2 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff();
  return {r0.dt_stable_s, 2.0 / std::sqrt(w2)};
}

}  // namespace

// Safe: dt_kernel <= 2/omega_max (tolerance 1e-6 relative for the finite-difference stiffness).
// Not absurd: dt_kernel >= 0.5 * 2/omega_max.
TEST(Hex8StableStep, SafeAndSharpForCubeAndDistortedHex) {
  const Material steel{"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
  const Material rubberish{"soft", MaterialKind::Elastic, 1100.0, 5e6, 0.45, {}};
  const Material auxetic{"aux", MaterialKind::Elastic, 1000.0, 1e9, -0.3, {}};
  for (const Material* mat : {&steel, &rubberish, &auxetic})
    for (double hg : {0.0, 0.1, 0.5})
      for (double dist : {0.0, 0.1, 0.25})
        for (unsigned seed : {1u, 2u, 3u}) {
          const auto c = stable_step(hex(0.01, dist, seed), *mat, hg);
          EXPECT_LE(c.dt_kernel, c.dt_exact * (1 + 1e-6))
              << mat->name << " hg " << hg << " distortion " << dist << " seed " << seed;
          EXPECT_GE(c.dt_kernel, 0.5 * c.dt_exact)
              << mat->name << " hg " << hg << " distortion " << dist << " seed " << seed;
          if (dist == 0.0 && seed == 1u)
            std::printf("%-6s hg %.1f cube: dt_kernel / (2/omega_max) = %.4f\n", mat->name.c_str(),
                        hg, c.dt_kernel / c.dt_exact);
          if (dist == 0.25 && seed == 1u)
            std::printf("%-6s hg %.1f distorted: dt_kernel / (2/omega_max) = %.4f\n",
                        mat->name.c_str(), hg, c.dt_kernel / c.dt_exact);
        }
}

// Bulk viscosity shortens the step by the factor sqrt(1 + xi^2) - xi, xi = Q1 + Q2 L |tr D| / c,
// in compression only (q = 0 at rest and in expansion, so dt_rest is the undamped bound).
TEST(Hex8StableStep, BulkViscosityShortensStepInCompression) {
  const Material steel{"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
  crashlink::model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  const auto x0 = hex(0.01, 0.0, 1);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  el::StepInfo step;
  auto st = el::make_hex8_state(part);
  const double dt_rest =
      el::hex8_internal_forces(part, steel, st, {x0.data(), v.data(), nullptr, f.data(), nullptr},
                               step)
          .dt_stable_s;
  // uniform compression rate tr D = -30 /s
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) v[3 * I + i] = -10.0 * (x0[3 * I + i] - 0.005);
  const double dt_comp =
      el::hex8_internal_forces(part, steel, st, {x0.data(), v.data(), nullptr, f.data(), nullptr},
                               step)
          .dt_stable_s;
  const double c = steel.dilatational_wave_speed_m_s(), L = 0.01;
  const double xi = 0.06 + 1.5 * L * 30.0 / c;
  // same geometry: ratio is exactly the damping factor (round-off, 1e-12)
  EXPECT_NEAR(dt_comp / dt_rest, std::sqrt(1 + xi * xi) - xi, 1e-12);
}
