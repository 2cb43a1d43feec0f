// An initial spin (model::InitialVelocity's angular velocity about an axis point, LS-DYNA
// *INITIAL_VELOCITY_GENERATION OMEGA; a rigid body's velocity given at a point): each node starts
// at v0 + omega x (x - c), so the kinetic energy at t = 0 is the rigid motion's, 1/2 M |v_G|^2 +
// 1/2 omega . J_G omega from the lumped masses; a free elastic block then keeps its angular
// momentum about its centre (internal forces exert no net moment); a rigid body spun about an
// axis off its centre moves its centre at v0 + omega x (c - p).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

constexpr Vec3 kOmega{0.0, 20.0, 100.0};  // rad/s
constexpr Vec3 kV0{1.0, -2.0, 0.5};       // m/s at the axis point
constexpr Vec3 kAxis{0.01, 0.02, -0.01};  // m: a point of the spin's axis, off the block

model::Model block(bool rigid) {
  model::Model m;
  m.name = "spinning block";
  m.materials.push_back({rigid ? "rigid" : "steel",
                         rigid ? materials::MaterialKind::Rigid : materials::MaterialKind::Elastic,
                         7850.0,
                         2.1e11,
                         0.3,
                         {}});
  model::Part p;
  p.name = "block";
  p.material = 0;
  model::generate_box(m, p, {{0.0, 0.0, 0.0}, {0.04, 0.02, 0.01}, {4, 2, 1}});
  if (rigid) {
    model::RigidBody rb;
    rb.name = "block";
    rb.parts = {0};
    rb.velocity_m_s = kV0;
    rb.angular_velocity_rad_s = kOmega;
    rb.velocity_at_point = true;
    rb.velocity_point_m = kAxis;
    m.rigid_bodies.push_back(rb);
  } else {
    model::InitialVelocity iv;
    for (std::size_t i = 0; i < m.nodes.count(); ++i) iv.nodes.push_back(static_cast<int>(i));
    iv.velocity_m_s = kV0;
    iv.angular_velocity_rad_s = kOmega;
    iv.centre_m = kAxis;
    m.initial_velocities.push_back(iv);
  }
  m.controls.end_time_s = 2e-4;
  m.controls.dt_max_s = 1e-6;  // (a rigid block alone gives no stable step)
  m.controls.bulk_viscosity = false;
  return m;
}

/// Centre, mass and the rigid motion's kinetic energy of the model's lumped masses.
struct Rigid {
  double mass = 0.0, ke = 0.0;
  Vec3 centre{};
};
Rigid rigid_motion(const model::Model& m, const std::vector<double>& mass) {
  Rigid r;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    r.mass += mass[i];
    r.centre =
        r.centre + mass[i] * Vec3{m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]};
  }
  r.centre = (1.0 / r.mass) * r.centre;
  const Vec3 vg = kV0 + cross(kOmega, r.centre - kAxis);
  r.ke = 0.5 * r.mass * dot(vg, vg);
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const Vec3 d = Vec3{m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]} - r.centre;
    const Vec3 w = cross(kOmega, d);
    r.ke += 0.5 * mass[i] * dot(w, w);
  }
  return r;
}

/// Angular momentum about the moving centre of mass at the solver's current state.
Vec3 spin_momentum(const integration::Solver& s) {
  const auto& m = s.model();
  const auto& x0 = m.nodes.x0;
  Vec3 c{}, p{};
  double mass = 0.0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const Vec3 x{x0[3 * i] + s.displacement()[3 * i], x0[3 * i + 1] + s.displacement()[3 * i + 1],
                 x0[3 * i + 2] + s.displacement()[3 * i + 2]};
    c = c + s.mass()[i] * x;
    mass += s.mass()[i];
  }
  c = (1.0 / mass) * c;
  Vec3 l{};
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const Vec3 x{x0[3 * i] + s.displacement()[3 * i], x0[3 * i + 1] + s.displacement()[3 * i + 1],
                 x0[3 * i + 2] + s.displacement()[3 * i + 2]};
    const Vec3 v{s.velocity_mid()[3 * i], s.velocity_mid()[3 * i + 1], s.velocity_mid()[3 * i + 2]};
    l = l + s.mass()[i] * cross(x - c, v);
    p = p + s.mass()[i] * v;
  }
  (void)p;
  return l;
}

TEST(InitialSpin, ElasticBlockStartsAsARigidSpinAndKeepsItsMomentum) {
  const model::Model m = block(false);
  integration::Solver s(m);
  s.initialize();
  const Rigid r = rigid_motion(m, s.mass());
  s.begin_cycle();
  const double ke0 = s.energy().kinetic_J;
  // v^{1/2} differs from v^0 by dt/2 a^0 (no force: none); the kinetic energy's product form
  // is that of v^0 to round-off
  EXPECT_NEAR(ke0, r.ke, 1e-12 * r.ke);
  // every node at v0 + omega x (x - c)
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const Vec3 x{m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]};
    const Vec3 v = kV0 + cross(kOmega, x - kAxis);
    for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(s.velocity_mid()[3 * i + d], v[d], 1e-9);
  }
  const Vec3 l0 = spin_momentum(s);
  double worst = 0.0, worst_balance = 0.0;
  for (;;) {
    s.end_cycle();
    s.begin_cycle();
    worst = std::max(worst, norm(spin_momentum(s) - l0));
    worst_balance = std::max(worst_balance, std::abs(s.energy().balance_J()));
    if (s.finished()) break;
  }
  std::printf(
      "[measured] spinning elastic block: kinetic at t = 0 %.9e J (rigid spin %.9e J), "
      "|L - L0| max %.2e of |L0| %.4e kg m^2/s over %lld cycles, |balance| %.2e of it\n",
      ke0, r.ke, worst, norm(l0), static_cast<long long>(s.cycle()), worst_balance / ke0);
  EXPECT_GT(s.cycle(), 100);
  EXPECT_LT(worst, 1e-12 * norm(l0));    // measured 1e-15
  EXPECT_LT(worst_balance, 1e-7 * ke0);  // measured 2.6e-9
}

TEST(InitialSpin, RigidBodySpunAboutAPointOffItsCentre) {
  const model::Model m = block(true);
  integration::Solver s(m);
  s.initialize();
  const auto& b = s.rigid_bodies()[0];
  const Vec3 vc = kV0 + cross(kOmega, b.centre0 - kAxis);
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_NEAR(b.velocity[d], vc[d], 1e-12);
    EXPECT_EQ(b.omega[d], kOmega[d]);
  }
  const Rigid r = rigid_motion(m, s.mass());
  s.begin_cycle();
  EXPECT_NEAR(s.energy().kinetic_J, r.ke, 1e-6 * r.ke);  // (the spin changes over dt/2)
}

}  // namespace
