// Consistency of the Belytschko-Tsay kernel's energy with its forces
// (shell_bt_forces.cpp, "Time levels"). Under a prescribed motion x(t), stepped
// as the integrator does (x^{n+1} = x(t^{n+1}), v^{n+1/2} = (x^{n+1} - x^n) /
// dt, omega^{n+1/2} = omega(t^{n+1/2})), the central-difference energy identity
// (docs/energy-balance.md) books the work of the nodal forces by the trapezoid
//   W = sum_n 1/2 (f^n + f^{n+1}) . du + 1/2 (m^n + m^{n+1}) . omega dt,
// and the kernel books the element energy E = sum_n (internal + hourglass
// increments). Their difference is the element's share of the balance error.
// With the velocity strains taken on the mid-step geometry x^{n+1/2} = x^{n+1}
// - dt/2 v it is O(dt^2) per run: with the strains of x^{n+1} it was O(dt) (the
// pairing 1/2 sigma^n (B^{n+1} - B^n) du is O(dt^2) per step), which is what
// made the balance error of shell scenes grow linearly with the step.
//
// Motion (SI units): a 4 x 3 patch of distorted quads, 0.3 m x 0.2 m, h = 2 mm,
// steel, spun rigidly by R(t) = exp(t W) through about 1 rad about an oblique
// axis while it is stretched (membrane strain 1e-3), bent (curvature 0.2 1/m)
// and sheared in its own frame, over T = 2 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/vec3.h"
#include "solver/elements/shell_bt.h"

using crashlink::operator*;
using crashlink::operator+;
using crashlink::operator-;

namespace {

using crashlink::Mat3;
using crashlink::Vec3;
namespace model = crashlink::model;
namespace materials = crashlink::materials;
namespace el = crashlink::elements;

constexpr double kT = 2e-3;  // duration [s]

struct Patch {
  std::vector<double> X;  // [3n] flat reference coordinates [m]
  model::Part part;
};

Patch make_patch(bool triangles, int points) {
  Patch p;
  const int nx = 4, ny = 3;
  const double ax = 0.3 / nx, ay = 0.2 / ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = i * ax - 0.15, y = j * ay - 0.1;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += 0.2 * ax * std::sin(1.7 * i + 2.3 * j);
        y += 0.2 * ay * std::cos(0.9 * i + 3.1 * j);
      }
      p.X.insert(p.X.end(), {x, y, 0.0});
    }
  p.part.name = "patch";
  p.part.kind = model::ElementKind::Shell4;
  p.part.thickness_m = 0.002;
  p.part.through_thickness_points = points;
  p.part.hourglass_coefficient = 0.1;
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles)
        p.part.connectivity.insert(p.part.connectivity.end(), {a, b, c, c, a, c, d, d});
      else
        p.part.connectivity.insert(p.part.connectivity.end(), {a, b, c, d});
    }
  for (std::size_t e = 0; e < p.part.element_count(); ++e)
    p.part.element_id.push_back(static_cast<std::int64_t>(e + 1));
  return p;
}

const Vec3 kSpin{0.3 * 300.0, -0.8 * 300.0, 0.5 * 300.0};  // [rad/s]: about 1 rad in T

/// Deformation amplitude s(t) in [0, 1], smooth, s(0) = 0.
double amp(double t) {
  return std::sin(0.5 * std::numbers::pi * t / kT);
}
double amp_rate(double t) {
  return 0.5 * std::numbers::pi / kT * std::cos(0.5 * std::numbers::pi * t / kT);
}

/// Body-frame displacement of reference point P at amplitude s: stretch, shear,
/// bending w.
Vec3 body_u(const Vec3& P, double s) {
  const double eps = 1e-3, gam = 5e-4, kap = 0.2;
  const double w = 0.5 * kap * (P[0] * P[0] - 0.5 * P[1] * P[1] + 0.7 * P[0] * P[1]);
  return s * Vec3{eps * P[0] + gam * P[1], -0.3 * eps * P[1], w};
}
/// Body-frame rotation of the normal per unit amplitude: (w_y, -w_x, 0).
Vec3 body_theta(const Vec3& P) {
  const double kap = 0.2;
  const double wx = kap * (P[0] + 0.35 * P[1]), wy = kap * (-0.5 * P[1] + 0.35 * P[0]);
  return {wy, -wx, 0.0};
}

Mat3 rot(double t) {
  return crashlink::rotation_from_vector(t * kSpin);
}

struct Balance {
  double element = 0.0;  // sum of the kernel's internal + hourglass increments [J]
  double nodal = 0.0;    // trapezoid work of the nodal forces and moments [J]
  double rel() const { return std::abs(element - nodal) / std::abs(element); }
};

Balance run(const Patch& p, const materials::Material& mat, int steps, bool spin, bool bulk) {
  const std::size_t nn = p.X.size() / 3;
  el::ShellState st = el::make_shell_state(p.part);
  const double dt = kT / steps;
  auto position = [&](std::size_t n, double t) {
    const Vec3 P{p.X[3 * n], p.X[3 * n + 1], p.X[3 * n + 2]};
    const Vec3 y = P + body_u(P, amp(t));
    return spin ? crashlink::mul(rot(t), y) : y;
  };
  std::vector<double> x(3 * nn), xn(3 * nn), v(3 * nn, 0.0), w(3 * nn, 0.0), f(3 * nn, 0.0),
      m(3 * nn, 0.0), fo(3 * nn), mo(3 * nn);
  for (std::size_t n = 0; n < nn; ++n)
    for (std::size_t c = 0; c < 3; ++c) x[3 * n + c] = position(n, 0.0)[c];
  el::StepInfo step{0.0, bulk};
  el::shell_internal_forces(p.part, mat, st, {x.data(), v.data(), w.data(), f.data(), m.data()},
                            step);
  Balance b;
  for (int it = 0; it < steps; ++it) {
    const double t1 = (it + 1) * dt, th = (it + 0.5) * dt;
    xn = x;
    fo = f;
    mo = m;
    const Mat3 Rh = rot(th);
    for (std::size_t n = 0; n < nn; ++n) {
      const Vec3 P{p.X[3 * n], p.X[3 * n + 1], p.X[3 * n + 2]};
      const Vec3 x1 = position(n, t1);
      const Vec3 th_rate = amp_rate(th) * body_theta(P);
      const Vec3 om = spin ? kSpin + crashlink::mul(Rh, th_rate) : th_rate;
      for (std::size_t c = 0; c < 3; ++c) {
        x[3 * n + c] = x1[c];
        v[3 * n + c] = (x1[c] - xn[3 * n + c]) / dt;
        w[3 * n + c] = om[c];
      }
    }
    std::fill(f.begin(), f.end(), 0.0);
    std::fill(m.begin(), m.end(), 0.0);
    step.dt_s = dt;
    const auto r = el::shell_internal_forces(
        p.part, mat, st, {x.data(), v.data(), w.data(), f.data(), m.data()}, step);
    b.element += r.internal_energy_increment_J + r.hourglass_energy_increment_J;
    for (std::size_t i = 0; i < 3 * nn; ++i)
      b.nodal += 0.5 * (fo[i] + f[i]) * v[i] * dt + 0.5 * (mo[i] + m[i]) * w[i] * dt;
  }
  return b;
}

materials::Material steel() {
  return {"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
}

// The element energy and the trapezoid work of the element's own nodal forces
// agree to second order in the step: halving dt divides their difference by 4.0
// (>= 3.5 asserted). With the velocity strains on x^{n+1} the ratio was 2.0
// (1.8 spinning) and the differences at 400 steps 2.5e-4 (quads) and 3.9e-5
// (triangles) of the energy, 0.27 and 0.069 spinning (a prestressed element
// spun by 2.5e-3 rad per step stretched by 1 - cos theta per step); now 1.0e-6
// and 1.6e-7, 6.4e-4 and 1.1e-4 spinning (the second-order term 1/4 (sigma^n -
// sigma^{n+1}) G' du du with the rigid part of du in it).
TEST(ShellBtEnergy, ElementEnergyMatchesNodalWorkToSecondOrder) {
  const auto mat = steel();
  for (bool triangles : {false, true}) {
    for (bool spin : {false, true}) {
      const Patch p = make_patch(triangles, 3);
      const Balance b1 = run(p, mat, 400, spin, true), b2 = run(p, mat, 800, spin, true);
      std::printf(
          "  %s, %s: E = %.6e J, |E - W| / E = %.3e (400 steps), %.3e "
          "(800), ratio %.2f\n",
          triangles ? "triangles" : "quads", spin ? "spinning" : "not spinning", b1.element,
          b1.rel(), b2.rel(), b1.rel() / b2.rel());
      EXPECT_GT(b1.element, 0.0);
      EXPECT_LT(b1.rel(), spin ? 2e-3 : 1e-5);
      EXPECT_GT(b1.rel() / b2.rel(), 3.5);
    }
  }
}

}  // namespace
