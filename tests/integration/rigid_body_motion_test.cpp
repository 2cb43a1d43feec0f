// A rigid body's held dofs (model::RigidBody::fixed, LS-DYNA *MAT_RIGID CON1/CON2) and prescribed
// motion (model::PrescribedVelocity::rigid_body, *BOUNDARY_PRESCRIBED_MOTION_RIGID) against their
// exact answers: a held rotation leaves the spin about the free axis constant (the reaction
// moments act about the held axes only, where the body does not turn: no work); a held
// translation under gravity carries the weight without moving; a prescribed velocity ramp moves
// the centre by the ramp's integral, its reaction's work being the kinetic energy it gave.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "core/state_archive.h"
#include "solver/io/result_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"
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
  // the discrete kinetic energy is 1/2 M v^{n-1/2} . v^{n+1/2}: within (a dt / v)^2 of 1/2 M v^2
  EXPECT_NEAR(s.energy().external_work_J, ke, 1e-7 * ke);
  EXPECT_LT(worst_balance, 1e-9 * ke);
}

// A ramp that starts moving at once (v(0) = 1 m/s, v(dt/2) another): the first cycle's reaction
// and work (the half step from t = 0) balance as the others: travel 0.05 (1 + 3) / 2 + 3 x 0.05 =
// 0.25 m, work 1/2 M (3^2 - 1^2) from the body's initial 1 m/s (its own 5 m/s replaced).
TEST(RigidBodyMotion, PrescribedVelocityFromTheFirstStep) {
  model::Model m = box();
  m.rigid_bodies[0].velocity_m_s = {5.0, 0.0, 0.0};
  m.rigid_bodies[0].angular_velocity_rad_s = {};
  model::PrescribedVelocity pv;
  pv.name = "push";
  pv.rigid_body = 0;
  pv.dof = 0;
  pv.velocity = model::Curve{{0.0, 0.05}, {1.0, 3.0}};
  m.prescribed_velocities.push_back(pv);
  integration::Solver s(m);
  double worst_balance = 0.0, e0 = -1.0;
  run(s, [&](const integration::Solver& sv) {
    if (e0 < 0.0) e0 = sv.energy().kinetic_J;
    worst_balance = std::max(worst_balance, std::abs(sv.energy().balance_J()));
  });
  const auto& b = s.rigid_bodies()[0];
  const double work = 0.5 * b.mass_kg * (9.0 - 1.0);
  std::printf(
      "[measured] ramp from 1 m/s: travel %.9f m (0.25), kinetic at t = 0 %.6f J "
      "(1/2 M 1^2 = %.6f), work %.6f J (%.6f), |balance| %.2e of it\n",
      b.centre[0] - b.centre0[0], e0, 0.5 * b.mass_kg, s.energy().external_work_J, work,
      worst_balance / work);
  // (the discrete kinetic energy's product form: within (a dt / v)^2 = 2e-7 of 1/2 M v^2)
  EXPECT_NEAR(e0, 0.5 * b.mass_kg, 1e-7 * b.mass_kg);
  EXPECT_NEAR(b.centre[0] - b.centre0[0], 0.25, 1e-6);
  EXPECT_NEAR(s.energy().external_work_J, work, 1e-7 * work);
  EXPECT_LT(worst_balance, 1e-9 * work);
}

// A held body's probe reads the acceleration it has (the reactions in its force): 0 under gravity
// where it is held, g along the free axes.
TEST(RigidBodyMotion, HeldBodyProbeReadsItsTrueAcceleration) {
  model::Model m = box();
  m.rigid_bodies[0].velocity_m_s = {};
  m.rigid_bodies[0].angular_velocity_rad_s = {};
  m.rigid_bodies[0].fixed = model::kUz;
  m.controls.gravity_m_s2 = {3.0, 0.0, -9.81};
  m.controls.end_time_s = 1e-3;
  m.probes.push_back({"box", model::Probe::Kind::RigidBody, 0});
  integration::Solver s(m);
  double worst_z = 0.0, worst_x = 0.0;
  run(s, [&](const integration::Solver& sv) {
    const auto p = sv.probe(sv.model().probes[0]);
    worst_z = std::max(worst_z, std::abs(p.acceleration_m_s2[2]));
    worst_x = std::max(worst_x, std::abs(p.acceleration_m_s2[0] - 3.0));
  });
  EXPECT_LT(worst_z, 1e-9);
  EXPECT_LT(worst_x, 1e-9);
}

// A checkpoint taken while a body is driven and held (the reactions' last values in it): the
// restored solver ends as the one that went on, to the bit.
TEST(RigidBodyMotion, CheckpointKeepsTheReactions) {
  model::Model m = box();
  m.rigid_bodies[0].fixed = model::kRx | model::kRy;
  model::PrescribedVelocity pv;
  pv.name = "push";
  pv.rigid_body = 0;
  pv.dof = 0;
  pv.velocity = model::Curve{{0.0, 0.05}, {0.0, 2.0}};
  m.prescribed_velocities.push_back(pv);
  const auto path = std::filesystem::temp_directory_path() /
                    ("crashlink_body_motion_" + std::to_string(::getpid()) + ".state.bin");
  integration::Solver a(m);
  a.initialize();
  for (int k = 0; k < 3000; ++k) {
    a.begin_cycle();
    a.end_cycle();
  }
  core::StateWriter w;
  a.save_state(w);
  w.save(path.string());
  integration::Solver b(m);
  b.initialize();
  b.restore_state(core::StateReader(path.string()));
  std::filesystem::remove(path);
  run_to_end(a);
  run_to_end(b);
  EXPECT_EQ(a.displacement(), b.displacement());
  EXPECT_EQ(a.energy().external_work_J, b.energy().external_work_J);
  EXPECT_EQ(a.energy().total_J(), b.energy().total_J());
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
  EXPECT_LT(worst_balance, 1e-4 * ke_max);  // measured 8e-6: the rotation's trapezoid rule
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

// A rigid ram (held but for z) driven down at 2 m/s on a steel bar standing on a finite wall, in
// mono and in multi with the bar's upper half and the ram in one domain, the lower half in the
// other: the ram travels its curve's integral in both (the motion follows the body into its
// domain), and the wall's impulse agrees within the coupling's 1 %.
TEST(RigidBodyMotion, DrivenRamOnAFiniteWallMonoAndMulti) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_driven_ram_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "ram.yaml") << R"(name: ram
controls: {end_time: 6.0e-5, history_interval: 1.0e-7}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
  rig: {type: rigid, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  low: {material: steel, mesh: {generator: box, origin: [0, 0, 0], size: [0.01, 0.01, 0.05], divisions: [2, 2, 10]}}
  high: {material: steel, merge_nodes: true, mesh: {generator: box, origin: [0, 0, 0.05], size: [0.01, 0.01, 0.05], divisions: [2, 2, 10]}}
  ram: {material: rig, merge_nodes: true, mesh: {generator: box, origin: [0, 0, 0.1], size: [0.01, 0.01, 0.005], divisions: [2, 2, 1]}}
rigid_bodies:
  ram: {parts: [ram], fix: [x, y, rx, ry, rz]}
prescribed_velocity:
  - {name: press, rigid_body: ram, dof: z, curve: {t: [0.0, 2.0e-5], v: [0.0, -2.0]}}
rigid_walls:
  floor: {nodes: {part: low}, point: [-0.01, -0.01, 0.0], normal: [0, 0, 1], edge: [1, 0, 0], length: 0.03, width: 0.03}
probes:
  ram: {rigid_body: ram}
domains:
  lower: {parts: [low]}
  upper: {parts: [high, ram]}
)";
  struct Out {
    double impulse = 0.0, travel = 0.0, t_end = 0.0;
  };
  const auto run = [&](const std::string& mode) {
    int status = 0;
    const auto out_dir = dir / mode;
    const std::string text = crashlink::testing::run_command(
        std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " + (dir / "ram.yaml").string() +
            " --mode " + mode + " --quiet --out " + out_dir.string(),
        status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
    Out o;
    const io::ResultReader r((out_dir / "result.h5").string());
    const io::ContactHistory h = r.wall("floor");
    for (std::size_t k = 1; k < h.size(); ++k)
      o.impulse +=
          0.5 * (h.force_N[3 * k + 2] + h.force_N[3 * k - 1]) * (h.time_s[k] - h.time_s[k - 1]);
    const auto ram = r.probe("ram");
    o.travel = ram.displacement_m.empty() ? 0.0 : ram.displacement_m.back();  // [3k]: its last z
    o.t_end = ram.time_s.empty() ? 0.0 : ram.time_s.back();
    return o;
  };
  const Out mono = run("mono"), multi = run("multi");
  std::printf(
      "[measured] driven ram on a finite wall: travel mono %.6f mm multi %.6f mm, wall "
      "impulse %.6e / %.6e N s\n",
      mono.travel * 1e3, multi.travel * 1e3, mono.impulse, multi.impulse);
  // the curve's integral to the last sample: 0.5 x 2 x 20 us + 2 m/s x (t - 20 us)
  const auto integral = [](double t) { return -(2.0e-5 + 2.0 * (t - 2.0e-5)); };
  std::printf(
      "[measured] ram travel against the curve's integral at its last sample: mono %.2e "
      "m (t %.6e s), multi %.2e m (t %.6e s)\n",
      mono.travel - integral(mono.t_end), mono.t_end, multi.travel - integral(multi.t_end),
      multi.t_end);
  // (the mid-step sampling's error at the ramp's kink, slope x dt^2: measured 2.5e-9 m)
  EXPECT_NEAR(mono.travel, integral(mono.t_end), 1e-8);
  EXPECT_NEAR(multi.travel, integral(multi.t_end), 1e-8);
  EXPECT_GT(mono.impulse, 0.1) << "the bar pushes on the wall";
  // multi at equal steps against mono: the layer coupling's differences (as the planar wall's
  // RigidWall.ForceHistoryInResultFileMonoAndMulti: 1 %)
  EXPECT_NEAR(multi.impulse, mono.impulse, 0.01 * mono.impulse);
  if (!::testing::Test::HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
