// Stable step of the Belytschko-Tsay shell against the exact highest frequency of the discrete
// system: stiffness K from the kernel itself (column j = forces after one step of length dt with a
// unit rate on dof j, divided by dt: exact for the linear rate form up to the O(dt) thickness
// change, dt = 1e-9 s), lumped M (translational mass and rotational inertia of
// shell_lumped_mass), omega_max^2 = max eig(M^-1/2 K M^-1/2) (Eigen3). Bulk viscosity off: it is
// a damping term, not part of K.
// Requirement: 0.4 * 2/omega_max <= dt_stable <= 2/omega_max (the translational step formula is
// stable with the rotary inertia chosen, yet not needlessly small).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "solver/elements/shell_bt.h"

namespace {

namespace model = crashlink::model;
namespace materials = crashlink::materials;
using crashlink::elements::NodalView;
using crashlink::elements::StepInfo;

struct Mesh {
  std::vector<double> x;  // [3n]
  model::Part part;
};

Mesh single(const std::vector<double>& xy, double h, bool triangle) {
  Mesh m;
  for (std::size_t i = 0; i < xy.size() / 2; ++i)
    m.x.insert(m.x.end(), {xy[2 * i], xy[2 * i + 1], 0.0});
  m.part.name = "one";
  m.part.kind = model::ElementKind::Shell4;
  m.part.thickness_m = h;
  m.part.through_thickness_points = 3;
  m.part.connectivity =
      triangle ? std::vector<std::int32_t>{0, 1, 2, 2} : std::vector<std::int32_t>{0, 1, 2, 3};
  m.part.element_id = {1};
  return m;
}

Mesh plate(int n, double a, double h) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double dx = (i > 0 && i < n && j > 0 && j < n) ? 0.15 * a * std::sin(3.1 * i + j) : 0;
      m.x.insert(m.x.end(), {i * a + dx, j * a, 0.02 * a * std::sin(1.0 * i * j)});
    }
  m.part.name = "plate";
  m.part.kind = model::ElementKind::Shell4;
  m.part.thickness_m = h;
  m.part.through_thickness_points = 5;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a0 = j * (n + 1) + i;
      m.part.connectivity.insert(m.part.connectivity.end(), {a0, a0 + 1, a0 + n + 2, a0 + n + 1});
      m.part.element_id.push_back(j * n + i + 1);
    }
  return m;
}

/// (dt_stable from the kernel, 2/omega_max from the eigenvalues).
std::pair<double, double> steps(const Mesh& m, const materials::Material& mat) {
  const std::size_t n = m.x.size() / 3, nd = 6 * n;
  std::vector<double> mass(n, 0.0), inertia(n, 0.0);
  crashlink::elements::shell_lumped_mass(m.part, mat, m.x.data(), mass.data(), inertia.data());
  Eigen::MatrixXd K =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nd), static_cast<Eigen::Index>(nd));
  const double dt = 1e-9;
  double dt_stable = 0.0;
  for (std::size_t j = 0; j < nd; ++j) {
    auto st = crashlink::elements::make_shell_state(m.part);
    std::vector<double> v(3 * n, 0.0), w(3 * n, 0.0), f(3 * n, 0.0), mo(3 * n, 0.0);
    const std::size_t node = j / 6, c = j % 6;
    (c < 3 ? v : w)[3 * node + c % 3] = 1.0;
    const NodalView nv{m.x.data(), v.data(), w.data(), f.data(), mo.data()};
    dt_stable = crashlink::elements::shell_internal_forces(m.part, mat, st, nv, StepInfo{dt, false})
                    .dt_stable_s;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        K(static_cast<Eigen::Index>(6 * i + k), static_cast<Eigen::Index>(j)) = f[3 * i + k] / dt;
        K(static_cast<Eigen::Index>(6 * i + 3 + k), static_cast<Eigen::Index>(j)) =
            mo[3 * i + k] / dt;
      }
  }
  Eigen::VectorXd minv(static_cast<Eigen::Index>(nd));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 6; ++k)
      minv(static_cast<Eigen::Index>(6 * i + k)) = 1.0 / std::sqrt(k < 3 ? mass[i] : inertia[i]);
  const Eigen::MatrixXd S = 0.5 * (K + K.transpose());
  EXPECT_LT((K - K.transpose()).norm(), 1e-6 * K.norm()) << "stiffness not symmetric";
  const Eigen::MatrixXd A = minv.asDiagonal() * S * minv.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A, Eigen::EigenvaluesOnly);
  const double w2 = es.eigenvalues().maxCoeff();
  return {dt_stable, 2.0 / std::sqrt(w2)};
}

materials::Material steel() {
  return materials::Material{"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
}

void check(const Mesh& m, const char* what) {
  const auto [dt, dt_exact] = steps(m, steel());
  EXPECT_LE(dt, dt_exact) << what;
  EXPECT_GE(dt, 0.4 * dt_exact) << what;
  std::printf("  %-40s dt_stable %.4e s  2/omega_max %.4e s  ratio %.3f\n", what, dt, dt_exact,
              dt / dt_exact);
}

}  // namespace

TEST(ShellBtStableStep, SingleElements) {
  const std::vector<double> square{0, 0, 1, 0, 1, 1, 0, 1};
  for (double h : {0.001, 0.01, 0.1, 0.3}) {
    Mesh m = single(square, h, false);
    check(m, ("unit square, h = " + std::to_string(h)).c_str());
  }
  check(single({0, 0, 2, 0, 2, 0.5, 0, 0.5}, 0.01, false), "rectangle 4:1, h = 0.01");
  check(single({0, 0, 5, 0, 5, 0.5, 0, 0.5}, 0.05, false), "rectangle 10:1, h = 0.05");
  check(single({0, 0, 1.2, 0.1, 0.9, 0.8, -0.1, 1.1}, 0.02, false), "distorted quad, h = 0.02");
  check(single({0, 0, 1, 0, 0.3, 0.9}, 0.01, true), "triangle, h = 0.01");
  check(single({0, 0, 1, 0, 0.5, 0.866}, 0.1, true), "equilateral triangle, h = 0.1");
  check(single({0, 0, 1, 0, 0.5, 0.866}, 0.001, true), "equilateral triangle, h = 0.001");
  check(single({0, 0, 1, 0, 0.5, 0.1}, 0.01, true), "flat isosceles triangle, h = 0.01");
  check(single({0, 0, 1, 0, 0.95, 0.2}, 0.01, true), "obtuse sliver triangle, h = 0.01");
  check(single({0, 0, 1, 0, 0.0, 1.0}, 0.01, true), "right triangle, h = 0.01");
  for (double r : {0.05, 0.15}) {
    Mesh m = single(square, 0.01, false);
    m.part.hourglass_coefficient = r;
    check(m, ("unit square, hourglass r = " + std::to_string(r)).c_str());
  }
}

TEST(ShellBtStableStep, SmallPlate) {
  check(plate(3, 0.1, 0.002), "3x3 plate, a = 0.1, h = 0.002");
  check(plate(3, 0.1, 0.02), "3x3 plate, a = 0.1, h = 0.02");
}
