// Stiffness-proportional (Rayleigh beta) damping in the element kernels (hex8.h, shell_bt.h):
// the viscous stress is beta C : D with beta = xi (2 / omega_max) fixed at the first call, the
// stable step shrinks by sqrt(1 + xi^2) - xi, rigid motion gives no damping force, per-element
// ratios override the part's, and the damping work is the trapezoid of the viscous stress.
//
// The power checks use a velocity field linear in x: for any element, sum_I f_I . v_I =
// V sigma : L (sum_I x_I (x) b_I = V I, sum_I b_I = 0), so the extra power of the damped kernel is
// V sigma_d : D with no need for the shape functions. The step is 1e-9 s with velocities of
// 1 m/s on 1 cm elements: the geometry moves by 1e-7 of the size between the configurations the
// kernel uses for D and for the forces, hence the 1e-6 relative tolerances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/errors.h"
#include "core/vec3.h"
#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"

using crashlink::operator*;
using crashlink::operator+;

namespace {

namespace el = crashlink::elements;
namespace model = crashlink::model;
using crashlink::Mat3;
using crashlink::Vec3;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

constexpr double kE = 210e9, kNu = 0.3, kRho = 7850.0;
constexpr double kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                 kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

Material steel() {
  return {"steel", MaterialKind::Elastic, kRho, kE, kNu, {}};
}

/// One hexahedron of edge h at the origin, corners moved by up to `distortion` h.
std::vector<double> hex_nodes(double h, double distortion, unsigned seed) {
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

model::Part hex_part(double xi) {
  model::Part p;
  p.name = xi > 0.0 ? "damped" : "plain";
  p.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  p.element_id = {1};
  p.damping_ratio = xi;
  return p;
}

el::StepInfo no_bulk(double dt) {
  el::StepInfo s;
  s.dt_s = dt;
  s.bulk_viscosity = false;
  return s;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double x : a) m = std::max(m, std::abs(x));
  return m;
}

// ---- hexahedron ------------------------------------------------------------------------------

struct HexRun {
  el::KernelResult init, step;
  std::vector<double> f;  // forces of the step call
  el::Hex8State st;
};

/// Initial call at x0 with v, then one step of dt to x0 + dt v with the same v.
HexRun run_hex(const model::Part& part, const std::vector<double>& x0, const std::vector<double>& v,
               double dt) {
  HexRun r{{}, {}, std::vector<double>(24, 0.0), el::make_hex8_state(part)};
  const auto mat = steel();
  std::vector<double> f(24, 0.0);
  r.init = el::hex8_internal_forces(part, mat, r.st, {x0.data(), v.data(), nullptr, f.data()},
                                    no_bulk(0.0));
  std::vector<double> x = x0;
  for (std::size_t i = 0; i < 24; ++i) x[i] += dt * v[i];
  r.step = el::hex8_internal_forces(part, mat, r.st, {x.data(), v.data(), nullptr, r.f.data()},
                                    no_bulk(dt));
  return r;
}

TEST(StiffnessDamping, HexViscousStressIsBetaTimesElasticModuliOnD) {
  const double h = 0.01, xi = 0.2, dt = 1e-9;
  const auto x0 = hex_nodes(h, 0.1, 7);
  // v = c + L x with a general (non-symmetric) L [1/s]: D = sym L.
  const double L[3][3] = {{40.0, -25.0, 10.0}, {35.0, -60.0, 15.0}, {-5.0, 20.0, 30.0}};
  const double c[3] = {0.3, -0.2, 0.1};
  std::vector<double> v(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i)
      v[3 * I + i] = c[i] + L[i][0] * x0[3 * I] + L[i][1] * x0[3 * I + 1] + L[i][2] * x0[3 * I + 2];

  const auto plain = run_hex(hex_part(0.0), x0, v, dt);
  const auto damped = run_hex(hex_part(xi), x0, v, dt);
  EXPECT_TRUE(plain.st.damping_beta_s.empty()) << "undamped part: no damping arrays";
  ASSERT_EQ(damped.st.damping_beta_s.size(), 1u);

  // beta = xi * (2 / omega_max), the undamped step bound at the first call (bulk viscosity off).
  const double dt0 = plain.init.dt_stable_s;
  EXPECT_NEAR(damped.st.damping_beta_s[0], xi * dt0, 1e-15 * xi * dt0);
  // Stable step with damping: dt0 (sqrt(1 + xi^2) - xi) (BLM section 6.3).
  EXPECT_NEAR(damped.init.dt_stable_s, dt0 * (std::sqrt(1.0 + xi * xi) - xi), 1e-14 * dt0);
  EXPECT_NEAR(damped.step.dt_stable_s, plain.step.dt_stable_s * (std::sqrt(1.0 + xi * xi) - xi),
              1e-6 * dt0);

  // Expected viscous stress and its power V sigma_d : D.
  const double beta = damped.st.damping_beta_s[0];
  const double mu = kE / (2.0 * (1.0 + kNu)), lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
  double D[3][3], trD = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) D[i][j] = 0.5 * (L[i][j] + L[j][i]);
    trD += D[i][i];
  }
  double sD = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      sD += beta * ((i == j ? lambda * trD : 0.0) + 2.0 * mu * D[i][j]) * D[i][j];
  std::vector<double> m(8, 0.0);
  el::hex8_lumped_mass(hex_part(0.0), steel(), x0.data(), m.data());
  double V = 0.0;
  for (double mi : m) V += mi;
  V /= kRho;
  const double power = V * sD;
  std::vector<double> df(24);
  for (std::size_t i = 0; i < 24; ++i) df[i] = damped.f[i] - plain.f[i];
  std::printf("[measured] hex: damping power %.9e W, expected V beta C:D:D = %.9e W\n", dot(df, v),
              power);
  EXPECT_NEAR(dot(df, v), power, 1e-6 * power);
  // Forces of a linear field are B^T sigma V: the damping force has zero resultant.
  for (int i = 0; i < 3; ++i) {
    double s = 0.0;
    for (int I = 0; I < 8; ++I) s += df[3 * I + i];
    EXPECT_NEAR(s, 0.0, 1e-9 * max_abs(df));
  }
  // Work over the step: the viscous stress of the initial call (same v) and of the step, so
  // 1/2 (sigma_d^0 + sigma_d^1) : D V dt = power dt; all of it in the internal energy.
  EXPECT_NEAR(damped.step.damping_energy_increment_J, power * dt, 1e-6 * power * dt);
  EXPECT_NEAR(damped.step.internal_energy_increment_J - plain.step.internal_energy_increment_J,
              damped.step.damping_energy_increment_J, 1e-6 * power * dt);
  EXPECT_EQ(plain.step.damping_energy_increment_J, 0.0);
  // Never in the material history: the stress is the undamped one.
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(damped.st.stress[k], plain.st.stress[k]);
}

TEST(StiffnessDamping, HexRigidMotionGivesNoDampingForce) {
  const double h = 0.01, xi = 0.3, dt = 1e-6;
  const auto X = hex_nodes(h, 0.15, 11);
  // Rigid spin + translation about the mid-step configuration x_mid = Q X (the kernel's D lives
  // there, hex8.h): v = vt + om x x_mid, x^{n+1} = x_mid + dt/2 v.
  const Vec3 axis{0.3, -1.0, 0.7}, vt{3.0, -2.0, 5.0}, om{700.0, -400.0, 1100.0};
  const Mat3 Q = crashlink::rotation_from_vector((1.1 / crashlink::norm(axis)) * axis);
  std::vector<double> xm(24), v(24), x1(24);
  for (std::size_t I = 0; I < 8; ++I) {
    const Vec3 p = crashlink::mul(Q, Vec3{X[3 * I], X[3 * I + 1], X[3 * I + 2]});
    const Vec3 w = crashlink::cross(om, p);
    for (std::size_t i = 0; i < 3; ++i) {
      xm[3 * I + i] = p[i];
      v[3 * I + i] = vt[i] + w[i];
      x1[3 * I + i] = p[i] + 0.5 * dt * v[3 * I + i];
    }
  }
  const auto part0 = hex_part(0.0), part1 = hex_part(xi);
  auto st0 = el::make_hex8_state(part0), st1 = el::make_hex8_state(part1);
  std::vector<double> f0(24, 0.0), f1(24, 0.0);
  // initial call at x_mid with the instantaneous rigid field (D = 0 there too), then one step
  el::hex8_internal_forces(part0, steel(), st0, {xm.data(), v.data(), nullptr, f0.data()},
                           no_bulk(0.0));
  el::hex8_internal_forces(part1, steel(), st1, {xm.data(), v.data(), nullptr, f1.data()},
                           no_bulk(0.0));
  std::fill(f0.begin(), f0.end(), 0.0);
  std::fill(f1.begin(), f1.end(), 0.0);
  el::hex8_internal_forces(part0, steel(), st0, {x1.data(), v.data(), nullptr, f0.data()},
                           no_bulk(dt));
  const auto r1 = el::hex8_internal_forces(part1, steel(), st1,
                                           {x1.data(), v.data(), nullptr, f1.data()}, no_bulk(dt));
  // Scale: the damping force of a strain rate |om| on this element, beta E |om| h^2.
  const double f_ref = st1.damping_beta_s[0] * kE * crashlink::norm(om) * h * h;
  double df = 0.0;
  for (std::size_t i = 0; i < 24; ++i) df = std::max(df, std::abs(f1[i] - f0[i]));
  std::printf("[measured] hex rigid motion: max |f_damped - f_plain| = %.3e of beta E |om| h^2\n",
              df / f_ref);
  EXPECT_LT(df, 1e-10 * f_ref);
  EXPECT_LT(max_abs(st1.damping_stress_Pa),
            1e-10 * st1.damping_beta_s[0] * kE * crashlink::norm(om));
  EXPECT_LT(std::abs(r1.damping_energy_increment_J), 1e-10 * f_ref * crashlink::norm(vt) * dt);
}

TEST(StiffnessDamping, HexElementRatiosOverrideThePartRatio) {
  // Three hexes in a row, part ratio 0.1 overridden per element by 0, 0.05, 0.2.
  const double h = 0.01;
  std::vector<double> x0;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 1; ++j)
      for (int k = 0; k <= 1; ++k) x0.insert(x0.end(), {i * h, j * h, k * h});
  auto id = [](int i, int j, int k) { return static_cast<std::int32_t>(4 * i + 2 * j + k); };
  model::Part part = hex_part(0.1);
  part.connectivity.clear();
  part.element_id = {1, 2, 3};
  for (int i = 0; i < 3; ++i)
    for (int kk = 0; kk < 2; ++kk)
      part.connectivity.insert(part.connectivity.end(),
                               {id(i, 0, kk), id(i + 1, 0, kk), id(i + 1, 1, kk), id(i, 1, kk)});
  part.element_damping_ratio = {0.0, 0.05, 0.2};
  std::vector<double> v(x0.size(), 0.0), f(x0.size(), 0.0);
  const el::NodalView nv{x0.data(), v.data(), nullptr, f.data()};
  model::Part plain = part;
  plain.damping_ratio = 0.0;
  plain.element_damping_ratio.clear();
  auto st0 = el::make_hex8_state(plain), st = el::make_hex8_state(part);
  const auto r0 = el::hex8_internal_forces(plain, steel(), st0, nv, no_bulk(0.0));
  const auto r = el::hex8_internal_forces(part, steel(), st, nv, no_bulk(0.0));
  ASSERT_EQ(st.damping_beta_s.size(), 3u);
  const double dt0 = r0.dt_stable_s;  // equal cubes: the same bound for all three
  EXPECT_EQ(st.damping_beta_s[0], 0.0);
  EXPECT_NEAR(st.damping_beta_s[1], 0.05 * dt0, 1e-15 * dt0);
  EXPECT_NEAR(st.damping_beta_s[2], 0.2 * dt0, 1e-15 * dt0);
  // the part's step is set by the most damped element
  EXPECT_NEAR(r.dt_stable_s, dt0 * (std::sqrt(1.04) - 0.2), 1e-14 * dt0);
  EXPECT_EQ(r.critical_element, 2);
  // all-zero element ratios switch the damping off whatever the part ratio
  part.element_damping_ratio = {0.0, 0.0, 0.0};
  EXPECT_FALSE(part.damped());
  EXPECT_TRUE(el::make_hex8_state(part).damping_beta_s.empty());
}

TEST(StiffnessDamping, StateBuiltForAnotherDampingIsAModelError) {
  const auto x0 = hex_nodes(0.01, 0.0, 1);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  auto st = el::make_hex8_state(hex_part(0.0));
  try {
    el::hex8_internal_forces(hex_part(0.05), steel(), st, {x0.data(), v.data(), nullptr, f.data()},
                             no_bulk(0.0));
    ADD_FAILURE() << "no error";
  } catch (const crashlink::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("make_hex8_state(part)"), std::string::npos) << e.what();
  }
}

// ---- Belytschko-Tsay shell ----------------------------------------------------------------

struct Shell {
  model::Part part;
  std::vector<double> x, v, w;
};

/// One square shell of edge a centred at the origin in the XY plane (so that the average of a
/// linear field over the nodes is its value at the centre).
Shell square_shell(double a, double thickness, double xi) {
  Shell s;
  s.part.name = "square";
  s.part.kind = model::ElementKind::Shell4;
  s.part.thickness_m = thickness;
  s.part.through_thickness_points = 5;
  s.part.connectivity = {0, 1, 2, 3};
  s.part.element_id = {1};
  s.part.damping_ratio = xi;
  const double p = 0.5 * a;
  s.x = {-p, -p, 0.0, p, -p, 0.0, p, p, 0.0, -p, p, 0.0};
  s.v.assign(12, 0.0);
  s.w.assign(12, 0.0);
  return s;
}

struct ShellRun {
  el::KernelResult init, step1, step2;
  std::vector<double> f, m;  // forces and moments of the second step
  el::ShellState st;
};

/// Initial call, then two steps of dt with the same nodal velocities (geometry kept: dt is tiny).
ShellRun run_shell(const Shell& s, const Material& mat, double dt) {
  ShellRun r{{},
             {},
             {},
             std::vector<double>(12, 0.0),
             std::vector<double>(12, 0.0),
             el::make_shell_state(s.part)};
  std::vector<double> f(12, 0.0), m(12, 0.0);
  const el::NodalView nv{s.x.data(), s.v.data(), s.w.data(), f.data(), m.data()};
  r.init = el::shell_internal_forces(s.part, mat, r.st, nv, no_bulk(0.0));
  r.step1 = el::shell_internal_forces(s.part, mat, r.st, nv, no_bulk(dt));
  const el::NodalView nv2{s.x.data(), s.v.data(), s.w.data(), r.f.data(), r.m.data()};
  r.step2 = el::shell_internal_forces(s.part, mat, r.st, nv2, no_bulk(dt));
  return r;
}

TEST(StiffnessDamping, ShellMembraneBendingAndShearViscousResultants) {
  const double a = 0.01, th = 0.001, xi = 0.2, dt = 1e-9;
  const double c11 = kE / (1.0 - kNu * kNu), c12 = kNu * c11, G = kE / (2.0 * (1.0 + kNu));
  const double kG = el::kShellShearFactor * G, A = a * a;
  for (bool plastic : {false, true}) {  // resultant form and point form of the history
    Material mat = steel();
    if (plastic) {
      mat.kind = MaterialKind::J2Plastic;
      mat.hardening = {{0.0, 0.1}, {250e6, 300e6}};
    }
    for (int field = 0; field < 3; ++field) {
      SCOPED_TRACE(::testing::Message() << (plastic ? "J2 " : "elastic ")
                                        << (field == 0   ? "membrane"
                                            : field == 1 ? "bending"
                                                         : "shear"));
      Shell s0 = square_shell(a, th, 0.0), s1 = square_shell(a, th, xi);
      double expected_per_beta = 0.0;  // power / beta
      for (Shell* s : {&s0, &s1})
        for (std::size_t n = 0; n < 4; ++n) {
          const double x = s->x[3 * n], y = s->x[3 * n + 1];
          if (field == 0) {  // v = L x in plane: d_xx = 30, d_yy = -20, 2 d_xy = 15 + 5
            s->v[3 * n] = 30.0 * x + 15.0 * y;
            s->v[3 * n + 1] = 5.0 * x - 20.0 * y;
          } else if (field == 1) {  // theta_y = k1 x, theta_x = -k2 y, and a twist
            s->w[3 * n] = -800.0 * y - 300.0 * x;
            s->w[3 * n + 1] = 500.0 * x + 200.0 * y;
          } else {  // w = g1 x + g2 y: gamma_xz = g1, gamma_yz = g2
            s->v[3 * n + 2] = 3.0 * x - 2.0 * y;
          }
        }
      if (field == 0) {
        const double dxx = 30.0, dyy = -20.0, gxy = 20.0;
        expected_per_beta =
            A * th * (c11 * (dxx * dxx + dyy * dyy) + 2.0 * c12 * dxx * dyy + G * gxy * gxy);
      } else if (field == 1) {
        const double kxx = 500.0, kyy = 800.0, kxy2 = 200.0 + 300.0;  // k_xx = B1.thy, ...
        expected_per_beta =
            A * th * th * th / 12.0 *
            (c11 * (kxx * kxx + kyy * kyy) + 2.0 * c12 * kxx * kyy + G * kxy2 * kxy2);
      } else {
        expected_per_beta = A * th * kG * (3.0 * 3.0 + 2.0 * 2.0);
      }
      const auto r0 = run_shell(s0, mat, dt);
      const auto r1 = run_shell(s1, mat, dt);
      EXPECT_TRUE(r0.st.damping_beta_s.empty());
      const double dt0 = r0.init.dt_stable_s;  // L_e / c
      const double beta = r1.st.damping_beta_s[0];
      EXPECT_NEAR(beta, xi * dt0, 1e-15 * xi * dt0);
      EXPECT_NEAR(r1.init.dt_stable_s, dt0 * (std::sqrt(1.0 + xi * xi) - xi), 1e-14 * dt0);
      double power = 0.0;
      for (std::size_t i = 0; i < 12; ++i)
        power += (r1.f[i] - r0.f[i]) * s1.v[i] + (r1.m[i] - r0.m[i]) * s1.w[i];
      const double expected = beta * expected_per_beta;
      std::printf("[measured] shell %s %s: damping power %.9e W, expected %.9e W\n",
                  plastic ? "J2" : "elastic",
                  field == 0   ? "membrane"
                  : field == 1 ? "bending"
                               : "shear",
                  power, expected);
      EXPECT_NEAR(power, expected, 1e-6 * expected);
      // Work: first step 1/2 (0 + sigma_d) : D (no viscous stress at the initial call: the shell
      // kernel takes no rates at dt = 0), second step sigma_d : D; both in the internal energy.
      EXPECT_NEAR(r1.step1.damping_energy_increment_J, 0.5 * expected * dt, 1e-6 * expected * dt);
      EXPECT_NEAR(r1.step2.damping_energy_increment_J, expected * dt, 1e-6 * expected * dt);
      EXPECT_NEAR(r1.step2.internal_energy_increment_J - r0.step2.internal_energy_increment_J,
                  expected * dt, 1e-6 * expected * dt);
      EXPECT_EQ(r0.step2.damping_energy_increment_J, 0.0);
      for (int c = 0; c < 5; ++c)
        for (int k = 0; k < 5; ++k) EXPECT_EQ(r1.st.sigma(c, k, 0), r0.st.sigma(c, k, 0));
      EXPECT_EQ(r1.st.thickness_m[0], r0.st.thickness_m[0]);
    }
  }
}

TEST(StiffnessDamping, ShellRigidMotionGivesNoDampingForce) {
  // A flat distorted quad in a tilted plane (flat: the Belytschko-Tsay strains of a warped quad
  // are not rigid-motion free), a rigid translation + spin (nodal omega = spin).
  model::Part part;
  part.name = "quad";
  part.kind = model::ElementKind::Shell4;
  part.thickness_m = 0.001;
  part.connectivity = {0, 1, 2, 3};
  part.element_id = {1};
  const Vec3 n0{0.2, -0.3, 1.0};
  const Vec3 nrm = (1.0 / crashlink::norm(n0)) * n0;
  const Vec3 c1 = crashlink::cross(nrm, Vec3{0.0, 1.0, 0.0});
  const Vec3 u1 = (1.0 / crashlink::norm(c1)) * c1, u2 = crashlink::cross(nrm, u1);
  const double p2[4][2] = {{0.0, 0.0}, {0.011, 0.001}, {0.012, 0.009}, {-0.001, 0.010}};
  std::vector<Vec3> X;
  for (const auto& p : p2) X.push_back(p[0] * u1 + p[1] * u2);
  // The step's motion is a rigid one from X: x^{n+1} = R X + dt vt, R = exp(dt [om]x), chord
  // velocities, nodal omega the step's rotation in the midpoint (Cayley) form 2 tan(theta/2)/dt n,
  // for which the mid-step velocity strains vanish exactly (shell_bt_forces.cpp).
  const Vec3 vt{3.0, -2.0, 5.0}, om{700.0, -400.0, 1100.0};
  const double dt1 = 1e-7, th = dt1 * crashlink::norm(om);
  const crashlink::Mat3 R = crashlink::rotation_from_vector(dt1 * om);
  const Vec3 wc = (2.0 * std::tan(0.5 * th) / th) * om;
  std::vector<double> x(12), x1(12), v(12), w(12);
  for (std::size_t n = 0; n < 4; ++n) {
    const Vec3 y = crashlink::mul(R, X[n]) + dt1 * vt;
    for (std::size_t i = 0; i < 3; ++i) {
      x[3 * n + i] = X[n][i];
      x1[3 * n + i] = y[i];
      v[3 * n + i] = (y[i] - X[n][i]) / dt1;
      w[3 * n + i] = wc[i];
    }
  }
  model::Part damped = part;
  damped.damping_ratio = 0.3;
  auto st0 = el::make_shell_state(part), st1 = el::make_shell_state(damped);
  std::vector<double> f0(12, 0.0), m0(12, 0.0), f1(12, 0.0), m1(12, 0.0);
  el::KernelResult r1;
  for (double dt : {0.0, dt1}) {
    if (dt > 0.0) x = x1;
    std::fill(f0.begin(), f0.end(), 0.0);
    std::fill(m0.begin(), m0.end(), 0.0);
    std::fill(f1.begin(), f1.end(), 0.0);
    std::fill(m1.begin(), m1.end(), 0.0);
    el::shell_internal_forces(part, steel(), st0,
                              {x.data(), v.data(), w.data(), f0.data(), m0.data()}, no_bulk(dt));
    r1 = el::shell_internal_forces(
        damped, steel(), st1, {x.data(), v.data(), w.data(), f1.data(), m1.data()}, no_bulk(dt));
  }
  const double beta = st1.damping_beta_s[0], h = 0.01;
  const double f_ref = beta * kE * crashlink::norm(om) * h * part.thickness_m;
  double df = 0.0, dm = 0.0;
  for (std::size_t i = 0; i < 12; ++i) {
    df = std::max(df, std::abs(f1[i] - f0[i]));
    dm = std::max(dm, std::abs(m1[i] - m0[i]));
  }
  std::printf(
      "[measured] shell rigid motion: max |df| = %.3e, |dm| / h = %.3e of beta E |om| h t\n",
      df / f_ref, dm / h / f_ref);
  EXPECT_LT(df, 1e-10 * f_ref);
  EXPECT_LT(dm, 1e-10 * f_ref * h);
  EXPECT_LT(std::abs(r1.damping_energy_increment_J), 1e-10 * f_ref * crashlink::norm(vt) * 1e-7);
}

}  // namespace
