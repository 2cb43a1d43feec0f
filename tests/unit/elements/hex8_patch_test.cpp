// Patch tests of the one-point hexahedron on a distorted 2x2x2 block (every node moved, the one
// interior node included): constant strain reproduced exactly, interior node in equilibrium, no
// stress or force under rigid translation and finite rigid rotation (Jaumann / Hughes-Winget).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"

namespace {

namespace el = crashlink::elements;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

constexpr double kE = 210e9, kNu = 0.3, kRho = 7850.0;

struct Block {
  crashlink::model::Part part;
  std::vector<double> x0;  // [3n]
  int interior = 13;       // node (1,1,1)
};

// 2x2x2 elements of edge 1 m, nodes moved randomly by up to 0.2 m.
Block make_block() {
  Block b;
  b.part.name = "patch";
  auto id = [](int i, int j, int k) { return i + 3 * j + 9 * k; };
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        b.x0.push_back(i + u(gen));
        b.x0.push_back(j + u(gen));
        b.x0.push_back(k + u(gen));
      }
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        for (int kk = 0; kk < 2; ++kk) {
          b.part.connectivity.push_back(id(i, j, k + kk));
          b.part.connectivity.push_back(id(i + 1, j, k + kk));
          b.part.connectivity.push_back(id(i + 1, j + 1, k + kk));
          b.part.connectivity.push_back(id(i, j + 1, k + kk));
        }
        b.part.element_id.push_back(100 + static_cast<int>(b.part.element_id.size()));
      }
  return b;
}

Material steel() {
  return {"steel", MaterialKind::Elastic, kRho, kE, kNu, {}};
}

el::KernelResult call(const Block& b, el::Hex8State& st, const std::vector<double>& x,
                      const std::vector<double>& v, std::vector<double>& f, double dt) {
  f.assign(x.size(), 0.0);
  el::NodalView nv{x.data(), v.data(), nullptr, f.data(), nullptr};
  el::StepInfo step;
  step.dt_s = dt;
  return el::hex8_internal_forces(b.part, steel(), st, nv, step);
}

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 rotation(const std::array<double, 3>& axis, double angle) {
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double a[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = (i == j ? c : 0.0) + (1 - c) * a[i] * a[j];
  r[0][1] -= s * a[2];
  r[0][2] += s * a[1];
  r[1][0] += s * a[2];
  r[1][2] -= s * a[0];
  r[2][0] -= s * a[1];
  r[2][1] += s * a[0];
  return r;
}

}  // namespace

// Linear velocity field v = L0 x^{n+1/2} + c: D = sym(L0) in every element to round-off, so
// sigma = dt C:D (hypoelastic, zero initial stress) to 1e-9 relative, and the interior node, whose
// force is sigma . d(total volume)/dx = 0, gets no net force (1e-9 of a typical nodal force
// |sigma| h^2). The hourglass rates of a linear field vanish (FB eq. 22), so no hourglass force.
TEST(Hex8Patch, ConstantStrainIsExactOnDistortedMesh) {
  Block b = make_block();
  auto st = el::make_hex8_state(b.part);
  const std::size_t n = b.x0.size() / 3, ne = b.part.element_count();
  std::vector<double> v(3 * n, 0.0), f;
  call(b, st, b.x0, v, f, 0.0);  // initial call: reference volumes

  const double L0[3][3] = {{2.0, -0.7, 0.4}, {1.1, -1.3, 0.5}, {-0.6, 0.9, 0.8}};  // [1/s]
  const double c0[3] = {0.3, -0.2, 0.1}, dt = 1e-4;
  std::vector<double> x(3 * n);
  for (std::size_t a = 0; a < n; ++a)
    for (int i = 0; i < 3; ++i) {
      double vi = c0[i];
      for (int j = 0; j < 3; ++j) vi += L0[i][j] * b.x0[3 * a + j];  // x0 is x^{n+1/2} here
      v[3 * a + i] = vi;
    }
  for (std::size_t k = 0; k < 3 * n; ++k) x[k] = b.x0[k] + 0.5 * dt * v[k];
  const auto r = call(b, st, x, v, f, dt);

  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  const double D[6] = {L0[0][0],
                       L0[1][1],
                       L0[2][2],
                       0.5 * (L0[0][1] + L0[1][0]),
                       0.5 * (L0[1][2] + L0[2][1]),
                       0.5 * (L0[2][0] + L0[0][2])};
  const double trD = D[0] + D[1] + D[2];
  double expect[6], scale = 0.0;
  for (int k = 0; k < 6; ++k) {
    expect[k] = dt * (2 * mu * D[k] + (k < 3 ? lambda * trD : 0.0));
    scale = std::max(scale, std::abs(expect[k]));
  }
  for (std::size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(st.stress[k * ne + e], expect[k], 1e-9 * scale) << "element " << e << " c " << k;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[3 * b.interior + i], 0.0, 1e-9 * scale);
  for (std::size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 12; ++k) EXPECT_NEAR(st.hourglass_force[k * ne + e], 0.0, 1e-9 * scale);
  EXPECT_GT(r.internal_energy_increment_J, 0.0);  // bulk viscosity dissipates in compression too
  EXPECT_NEAR(r.hourglass_energy_increment_J, 0.0, 1e-12 * r.internal_energy_increment_J);
}

// Rigid translation over 100 steps: velocity gradients are round-off (1e-16 v/h), so the stress
// stays below 1e-3 Pa (1e-14 of E) and so do the forces (h = 1 m).
TEST(Hex8Patch, RigidTranslationGivesNoStress) {
  Block b = make_block();
  auto st = el::make_hex8_state(b.part);
  const std::size_t n = b.x0.size() / 3;
  std::vector<double> x = b.x0, v(3 * n), f;
  call(b, st, x, v, f, 0.0);
  const double dt = 1e-3;
  for (std::size_t a = 0; a < n; ++a) {
    v[3 * a] = 30.0;
    v[3 * a + 1] = -20.0;
    v[3 * a + 2] = 10.0;
  }
  for (int s = 0; s < 100; ++s) {
    for (std::size_t k = 0; k < 3 * n; ++k) x[k] += dt * v[k];
    call(b, st, x, v, f, dt);
  }
  for (double s : st.stress) EXPECT_NEAR(s, 0.0, 1e-3);
  for (double fi : f) EXPECT_NEAR(fi, 0.0, 1e-3);
}

// Finite rigid rotation, 30 degrees about a skew axis in 300 central-difference steps, starting
// from a uniform prestress sigma0. With D and W evaluated at x^{n+1/2}, D = 0 and the
// Hughes-Winget rotation equals the incremental rotation exactly, so sigma = Q sigma0 Q^T to
// round-off (1e-9 relative after 300 steps); without prestress nothing appears at all (forces and
// stresses below 1e-3 Pa, N). Forces of the rotated uniform prestress are self-equilibrated: the
// interior node carries none (1e-9 |sigma0| h^2).
TEST(Hex8Patch, FiniteRigidRotationIsObjective) {
  for (bool prestress : {false, true}) {
    Block b = make_block();
    auto st = el::make_hex8_state(b.part);
    const std::size_t n = b.x0.size() / 3, ne = b.part.element_count();
    const double s0[6] = {100e6, -50e6, 30e6, 40e6, -20e6, 10e6};
    if (prestress)
      for (std::size_t e = 0; e < ne; ++e)
        for (int k = 0; k < 6; ++k) st.stress[k * ne + e] = s0[k];
    const std::array<double, 3> axis{1.0, 2.0, 3.0};
    const double total = M_PI / 6.0, dt = 1e-4;
    const int steps = 300;
    auto config = [&](double angle) {
      const Mat3 q = rotation(axis, angle);
      std::vector<double> x(3 * n);
      for (std::size_t a = 0; a < n; ++a)
        for (int i = 0; i < 3; ++i) {
          double xi = 1.0;  // rotate about (1,1,1)
          for (int j = 0; j < 3; ++j) xi += q[i][j] * (b.x0[3 * a + j] - 1.0);
          x[3 * a + i] = xi;
        }
      return x;
    };
    std::vector<double> xn = b.x0, v(3 * n, 0.0), f;
    call(b, st, xn, v, f, 0.0);
    for (int s = 1; s <= steps; ++s) {
      const auto x1 = config(total * s / steps);
      for (std::size_t k = 0; k < 3 * n; ++k) v[k] = (x1[k] - xn[k]) / dt;
      call(b, st, x1, v, f, dt);
      xn = x1;
    }
    const Mat3 q = rotation(axis, total);
    const double S[3][3] = {{s0[0], s0[3], s0[5]}, {s0[3], s0[1], s0[4]}, {s0[5], s0[4], s0[2]}};
    double rs[3][3] = {};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int m = 0; m < 3; ++m) rs[i][j] += q[i][k] * S[k][m] * q[j][m];
    const int vi[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
    for (std::size_t e = 0; e < ne; ++e)
      for (int k = 0; k < 6; ++k) {
        const double expect = prestress ? rs[vi[k][0]][vi[k][1]] : 0.0;
        EXPECT_NEAR(st.stress[k * ne + e], expect, prestress ? 1e-9 * 100e6 : 1e-3)
            << "element " << e << " component " << k;
      }
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(f[3 * b.interior + i], 0.0, prestress ? 1e-9 * 100e6 : 1e-3);
    for (double qh : st.hourglass_force) EXPECT_NEAR(qh, 0.0, 1e-3);
  }
}
