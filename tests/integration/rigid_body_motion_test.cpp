// A rigid body's held dofs (model::RigidBody::fixed, LS-DYNA *MAT_RIGID CON1/CON2) and prescribed
// motion (model::PrescribedVelocity::rigid_body, *BOUNDARY_PRESCRIBED_MOTION_RIGID) against their
// exact answers: a held rotation leaves the spin about the free axis constant (the reaction
// moments act about the held axes only, where the body does not turn: no work); a held
// translation under gravity carries the weight without moving; a prescribed velocity ramp moves
// the centre by the ramp's integral, its reaction's work being the kinetic energy it gave.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solver/core/errors.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

/// An asymmetric rigid box (not about a principal axis at t = 0), 1e4 steps of 10 us.
model::Model box() {
  model::Model m;
  m.name = "held box";
  m.materials.push_back({"rigid", materials::MaterialKind::Rigid, 2700.0, 70e9, 0.3, {}});
  model::Part p;
  p.name = "box";
  p.material = 0;
  model::generate_box(m, p, {{-0.05, -0.1, -0.15}, {0.1, 0.2, 0.3}, {2, 3, 4}});
  model::RigidBody rb;
  rb.name = "box";
  rb.parts = {0};
  rb.velocity_m_s = {1.0, -2.0, 3.0};
  rb.angular_velocity_rad_s = {20.0, -5.0, 12.0};
  m.rigid_bodies.push_back(rb);
  m.controls.dt_max_s = 1e-5;
  m.controls.end_time_s = 0.1;
  return m;
}

// x and y rotations held (CON2 4): the body spins about z at its initial 12 rad/s, whatever its
// inertia's products; translations free.
TEST(RigidBodyMotion, HeldRotationsLeaveTheSpinAboutTheFreeAxis) {
  model::Model m = box();
  m.rigid_bodies[0].fixed = model::kRx | model::kRy;
  integration::Solver s(m);
  double worst_spin = 0.0, worst_held = 0.0, worst_balance = 0.0, e0 = 0.0;
  run(s, [&](const integration::Solver& sv) {
    const auto& b = sv.rigid_bodies()[0];
    worst_spin = std::max(worst_spin, std::abs(b.omega[2] - 12.0));
    worst_held = std::max({worst_held, std::abs(b.omega[0]), std::abs(b.omega[1])});
    if (e0 == 0.0) e0 = sv.energy().total_J();
    worst_balance = std::max(worst_balance, std::abs(sv.energy().balance_J()));
  });
  const auto& b = s.rigid_bodies()[0];
  std::printf(
      "[measured] held x, y rotations: |omega_z - 12| %.2e rad/s, |omega_x,y| %.2e, "
      "|balance| %.2e E0, centre x %.9f m\n",
      worst_spin, worst_held, worst_balance / e0, b.centre[0] - b.centre0[0]);
  EXPECT_LT(worst_spin, 1e-9);
  EXPECT_LT(worst_held, 1e-12);
  EXPECT_LT(worst_balance, 1e-9 * e0);
  EXPECT_NEAR(b.centre[0] - b.centre0[0], 0.1, 1e-12);  // v_x 1 m/s for 0.1 s
}

// z held under gravity (CON1 3): the centre stays at its height, moves on in x and y.
TEST(RigidBodyMotion, HeldTranslationCarriesTheWeight) {
  model::Model m = box();
  m.rigid_bodies[0].fixed = model::kUz | model::kRx | model::kRy | model::kRz;
  m.controls.gravity_m_s2 = {0.0, 0.0, -9.81};
  integration::Solver s(m);
  double worst_balance = 0.0, e0 = 0.0;
  run(s, [&](const integration::Solver& sv) {
    if (e0 == 0.0) e0 = sv.energy().total_J();
    worst_balance = std::max(worst_balance, std::abs(sv.energy().balance_J()));
  });
  const auto& b = s.rigid_bodies()[0];
  EXPECT_EQ(b.centre[2], b.centre0[2]);
  EXPECT_NEAR(b.centre[1] - b.centre0[1], -0.2, 1e-12);
  EXPECT_EQ(b.omega[0], 0.0);
  EXPECT_EQ(b.omega[2], 0.0);
  EXPECT_LT(worst_balance, 1e-12 * e0);
}

// v_x prescribed: 0 -> 2 m/s over 50 ms, then 2 m/s: the centre moves 0.05 + 0.1 = 0.15 m; the
// reaction's work is the kinetic energy it gave (1/2 M 2^2 more along x).
TEST(RigidBodyMotion, PrescribedVelocityRampMovesByItsIntegral) {
  model::Model m = box();
  m.rigid_bodies[0].velocity_m_s = {5.0, 0.0, 0.0};  // replaced by the curve's v(0) = 0
  m.rigid_bodies[0].angular_velocity_rad_s = {};
  model::PrescribedVelocity pv;
  pv.name = "push";
  pv.rigid_body = 0;
  pv.dof = 0;
  pv.velocity = model::Curve{{0.0, 0.05}, {0.0, 2.0}};
  m.prescribed_velocities.push_back(pv);
  integration::Solver s(m);
  double worst_balance = 0.0;
  run(s, [&](const integration::Solver& sv) {
    worst_balance = std::max(worst_balance, std::abs(sv.energy().balance_J()));
  });
  const auto& b = s.rigid_bodies()[0];
  const double ke = 0.5 * b.mass_kg * 4.0;
  std::printf(
      "[measured] prescribed ramp: travel %.9f m (0.15), external work %.6f J, "
      "1/2 M v^2 %.6f J, |balance| %.2e of it\n",
      b.centre[0] - b.centre0[0], s.energy().external_work_J, ke, worst_balance / ke);
  EXPECT_NEAR(b.centre[0] - b.centre0[0], 0.15, 1e-6);
  EXPECT_EQ(b.velocity[0], 2.0);
  EXPECT_NEAR(s.energy().external_work_J, ke, 1e-3 * ke);
  EXPECT_LT(worst_balance, 1e-3 * ke);
}

// The spin about z prescribed (10 rad/s) on the tumbling box: omega_z follows it at every step,
// the free x and y rotations keep their own dynamics, the balance holds.
TEST(RigidBodyMotion, PrescribedSpinHoldsTheBalance) {
  model::Model m = box();
  model::PrescribedVelocity pv;
  pv.name = "spin";
  pv.rigid_body = 0;
  pv.dof = 5;
  pv.velocity = model::Curve::constant(10.0);
  m.prescribed_velocities.push_back(pv);
  integration::Solver s(m);
  double worst_spin = 0.0, worst_balance = 0.0, ke_max = 0.0, free_max = 0.0;
  run(s, [&](const integration::Solver& sv) {
    const auto& b = sv.rigid_bodies()[0];
    worst_spin = std::max(worst_spin, std::abs(b.omega[2] - 10.0));
    free_max = std::max(free_max, std::abs(b.omega[0]));
    ke_max = std::max(ke_max, sv.energy().kinetic_J);
    worst_balance = std::max(worst_balance, std::abs(sv.energy().balance_J()));
  });
  std::printf(
      "[measured] prescribed spin: |omega_z - 10| %.2e, max |omega_x| %.3f rad/s, "
      "|balance| %.2e of the peak kinetic energy\n",
      worst_spin, free_max, worst_balance / ke_max);
  EXPECT_LT(worst_spin, 1e-9);
  EXPECT_GT(free_max, 1.0) << "the free axes still turn";
  EXPECT_LT(worst_balance, 1e-3 * ke_max);
}

// A dof held and prescribed at once is refused, naming the body.
TEST(RigidBodyMotion, HeldAndPrescribedIsRefused) {
  model::Model m = box();
  m.rigid_bodies[0].fixed = model::kUx;
  model::PrescribedVelocity pv;
  pv.name = "push";
  pv.rigid_body = 0;
  pv.dof = 0;
  pv.velocity = model::Curve::constant(1.0);
  m.prescribed_velocities.push_back(pv);
  try {
    integration::Solver s(m);
    s.initialize();
    FAIL() << "not refused";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("rigid body 'box': its velocity along x is held or "
                                         "prescribed twice (again by prescribed motion 'push')"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
