// Spot welds (model::RigidBody::Failure, LS-DYNA *CONSTRAINED_SPOTWELD): a lap joint of two steel
// strips, the lower held at its far edge, the upper pulled at its far edge, joined by two welds
// across the 1 mm gap where they overlap. The welds carry the pull in shear:
//  - strong welds hold: the held strip's reaction grows with the pull, the energy balance holds;
//  - welds of shear strength S let go when the shear they carry reaches S (at the step it is
//    crossed: within a few % of S), at one instant for the two (the joint is symmetric), and
//    the upper strip then moves on its own, the lower one unloaded; the balance still holds.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/state_archive.h"
#include "solver/deck/model_from_deck.h"
#include "solver/deck_writer/deck_writer.h"
#include "solver/integration/solver.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

/// A weld (no failure yet) of the nodes at a and at b [m].
model::RigidBody weld(const model::Model& m, const std::string& name, const Vec3& a,
                      const Vec3& b) {
  model::RigidBody w;
  w.name = name;
  for (const Vec3& x : {a, b})
    for (std::size_t i = 0; i < m.nodes.count(); ++i)
      if (std::abs(m.nodes.x0[3 * i] - x[0]) < 1e-9 &&
          std::abs(m.nodes.x0[3 * i + 1] - x[1]) < 1e-9 &&
          std::abs(m.nodes.x0[3 * i + 2] - x[2]) < 1e-9)
        w.nodes.push_back(static_cast<std::int32_t>(i));
  EXPECT_EQ(w.nodes.size(), 2u) << name;
  return w;
}

model::Model lap_joint(double shear_strength_N) {
  model::Model m = io::parse_scenario(R"(name: lap joint
controls: {end_time: 4.0e-4}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  lower: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.05, 0.01], normal: z, divisions: [5, 1]}}
  upper: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0.04, 0, 0.001], size: [0.05, 0.01], normal: z, divisions: [5, 1]}}
boundary:
  - {nodes: {part: lower, box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}, fix: all}
prescribed_velocity:
  - {nodes: {part: upper, box: {min: [0.0899, -1, -1], max: [1, 1, 1]}}, dof: x, curve: {t: [0.0, 1.0e-4, 1.0], v: [0.0, 1.0, 1.0]}}
)",
                                      "lap.yaml");
  // the welds at x = 0.05, y = 0 and 0.01: the lower strip's node under the upper's
  for (double y : {0.0, 0.01}) {
    model::RigidBody w = weld(m, y == 0.0 ? "weld_a" : "weld_b", {0.05, y, 0.0}, {0.05, y, 0.001});
    w.failure.shear_N = shear_strength_N;
    w.failure.normal_N = 1e9;
    m.rigid_bodies.push_back(w);
  }
  return m;
}

struct Outcome {
  std::vector<integration::WeldFailure> failures;
  double balance_max_J = 0.0, energy_max_J = 0.0;
  double lower_internal_at_failure_J = 0.0, lower_internal_end_J = 0.0;
  double max_shear_before_N = 0.0;  ///< the largest weld shear seen before any failure
};

Outcome pull(double strength_N) {
  const model::Model m = lap_joint(strength_N);
  integration::Solver s(m);
  s.initialize();
  Outcome o;
  for (;;) {
    s.begin_cycle();
    const auto& e = s.energy();
    o.balance_max_J = std::max(o.balance_max_J, std::abs(e.balance_J()));
    o.energy_max_J = std::max(o.energy_max_J, std::abs(e.external_work_J));
    if (o.failures.empty() && !s.weld_failures().empty())
      o.lower_internal_at_failure_J = s.parts()[0].internal_energy_J;
    o.failures = s.weld_failures();
    if (s.finished()) break;
    s.end_cycle();
  }
  o.lower_internal_end_J = s.parts()[0].internal_energy_J;
  return o;
}

TEST(SpotWeld, StrongWeldsHoldTheJoint) {
  const Outcome o = pull(1e9);
  EXPECT_TRUE(o.failures.empty());
  std::printf(
      "[measured] strong welds: lower strip's internal energy %.3e J, balance at most "
      "%.2e J of %.3e J of work\n",
      o.lower_internal_end_J, o.balance_max_J, o.energy_max_J);
  EXPECT_GT(o.lower_internal_end_J, 1e-3) << "the pull reaches the held strip through the welds";
  EXPECT_LT(o.balance_max_J, 1e-3 * o.energy_max_J);
}

TEST(SpotWeld, WeakWeldsLetGoAtTheirStrength) {
  const double strength = 2000.0;  // N: the strong joint's welds carry ~10 kN by the end
  const Outcome o = pull(strength);
  ASSERT_EQ(o.failures.size(), 2u) << "both welds fail";
  for (const auto& f : o.failures)
    std::printf("[measured] %s failed at %.4e s: shear %.1f N (strength %.0f N), normal %.1f N\n",
                f.name.c_str(), f.time_s, f.shear_N, strength, f.normal_N);
  EXPECT_EQ(o.failures[0].time_s, o.failures[1].time_s) << "a symmetric joint";
  for (const auto& f : o.failures) {
    EXPECT_GE(f.shear_N, strength);
    EXPECT_LT(f.shear_N, 1.05 * strength) << "the step at which it is crossed";
  }
  std::printf(
      "[measured] lower strip's internal energy at failure %.3e J, at the end %.3e J; "
      "balance at most %.2e J of %.3e J of work\n",
      o.lower_internal_at_failure_J, o.lower_internal_end_J, o.balance_max_J, o.energy_max_J);
  // let go: the held strip keeps only its elastic ringing, no more work from the pull
  EXPECT_LT(o.lower_internal_end_J, 2.0 * o.lower_internal_at_failure_J);
  EXPECT_LT(o.balance_max_J, 1e-3 * o.energy_max_J);
}

/// Two stacked 2 x 2 plates (1 mm apart), the lower held at its rim, the upper moved along z at
/// its rim; a weld joins the centres. SN 100 N alone: pulled apart it fails in tension (its
/// normal force then just past 100 N), pushed together it holds (SN acts in tension only; the
/// weld is compressed, its small tensile rebounds stay below SN).
std::vector<integration::WeldFailure> peel(double vz, double normal_N = 100.0) {
  model::Model m = io::parse_scenario(R"(name: peel
controls: {end_time: 3.0e-4}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  lower: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.02, 0.02], normal: z, divisions: [2, 2]}}
  upper: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0.001], size: [0.02, 0.02], normal: z, divisions: [2, 2]}}
boundary:
  - {nodes: {part: lower, box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}, fix: all}
  - {nodes: {part: lower, box: {min: [0.0199, -1, -1], max: [1, 1, 1]}}, fix: all}
prescribed_velocity:
  - {nodes: {part: upper, box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}, dof: z, value: )" +
                                          std::to_string(vz) + R"(}
  - {nodes: {part: upper, box: {min: [0.0199, -1, -1], max: [1, 1, 1]}}, dof: z, value: )" +
                                          std::to_string(vz) + R"(}
)",
                                      "peel.yaml");
  model::RigidBody w = weld(m, "centre", {0.01, 0.01, 0.0}, {0.01, 0.01, 0.001});
  w.failure.normal_N = normal_N;
  w.failure.exp_n = 2.0;
  m.rigid_bodies.push_back(w);
  integration::Solver s(m);
  s.initialize();
  for (;;) {
    s.begin_cycle();
    if (s.finished()) break;
    s.end_cycle();
  }
  return s.weld_failures();
}

TEST(SpotWeld, PulledApartItFailsInTensionPushedTogetherItHolds) {
  const auto apart = peel(0.5), together = peel(-0.5);
  ASSERT_EQ(apart.size(), 1u);
  std::printf(
      "[measured] peel: the weld let go at %.4e s in tension %.1f N (SN 100 N), shear "
      "%.2f N\n",
      apart[0].time_s, apart[0].normal_N, apart[0].shear_N);
  EXPECT_GE(apart[0].normal_N, 100.0);
  EXPECT_LT(apart[0].normal_N, 120.0) << "the step at which it is crossed";
  EXPECT_TRUE(together.empty()) << "compression does not count";
}

/// A weld of two hexahedra's nodes (no rotational inertia: no inertia about the weld's line
/// without the solver's hundredth) runs: two steel cubes 1 mm apart, the upper one sliding.
TEST(SpotWeld, BetweenSolidNodesItRuns) {
  model::Model m = io::parse_scenario(R"(name: cubes
controls: {end_time: 1.0e-4}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  lower: {material: steel, mesh: {generator: box, origin: [0, 0, 0], size: [0.01, 0.01, 0.01], divisions: [2, 2, 2]}}
  upper: {material: steel, mesh: {generator: box, origin: [0, 0, 0.011], size: [0.01, 0.01, 0.01], divisions: [2, 2, 2]}}
initial_velocity:
  - {part: upper, velocity: [1.0, 0.3, 0.0]}
)",
                                      "cubes.yaml");
  model::RigidBody w = weld(m, "w", {0.005, 0.005, 0.01}, {0.005, 0.005, 0.011});
  ASSERT_EQ(w.nodes.size(), 2u);
  w.failure.shear_N = 1e9;
  w.failure.exp_m = 2.0;
  m.rigid_bodies.push_back(w);
  integration::Solver s(m);
  s.initialize();
  double e0 = 0.0, worst = 0.0;
  for (;;) {
    s.begin_cycle();
    if (e0 == 0.0) e0 = s.energy().kinetic_J;
    worst = std::max(worst, std::abs(s.energy().balance_J()));
    if (s.finished()) break;
    s.end_cycle();
  }
  std::printf("[measured] weld of solid nodes: balance at most %.2e J of %.3e J\n", worst, e0);
  EXPECT_TRUE(s.weld_failures().empty());
  EXPECT_LT(worst, 1e-3 * e0);
}

// Written as *CONSTRAINED_SPOTWELD in mm-t-s and read back: the same welds (nodes, strengths,
// exponents) and the same failure at the same step (to the conversions' round-off).
TEST(SpotWeld, ExportedDeckFailsAlike) {
  const model::Model m = lap_joint(2000.0);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_spot_weld_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto text = deck_writer::export_deck(m, *deck::find_unit_system("mm-t-s"), "lap.k", "t");
  std::ofstream(dir / "lap.k") << text.deck;
  const model::Model d = deck::read_deck((dir / "lap.k").string(), {"mm-t-s", {}}).model;
  ASSERT_EQ(d.rigid_bodies.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(d.rigid_bodies[k].nodes, m.rigid_bodies[k].nodes);
    EXPECT_NEAR(d.rigid_bodies[k].failure.shear_N, 2000.0, 1e-9);
    EXPECT_NEAR(d.rigid_bodies[k].failure.normal_N, 1e9, 1e-3);
    EXPECT_EQ(d.rigid_bodies[k].failure.exp_m, 2.0);
  }
  integration::Solver a(m), b(d);
  a.set_step_hold(true);  // as `crashlink run` below (run::run_single_domain)
  b.set_step_hold(true);
  a.initialize();
  b.initialize();
  for (;;) {
    a.begin_cycle();
    b.begin_cycle();
    if (a.finished()) break;
    a.end_cycle();
    b.end_cycle();
  }
  ASSERT_EQ(a.weld_failures().size(), 2u);
  ASSERT_EQ(b.weld_failures().size(), 2u);
  // mm-t-s: the conversions' round-off, the same cycle
  EXPECT_NEAR(b.weld_failures()[0].time_s, a.weld_failures()[0].time_s,
              1e-12 * a.weld_failures()[0].time_s);
  EXPECT_NEAR(b.weld_failures()[0].shear_N, a.weld_failures()[0].shear_N,
              1e-6 * a.weld_failures()[0].shear_N);
  // `crashlink run` of the deck says which welds let go, when and under what
  int status = 0;
  const std::string out = testing::run_command(
      std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " + (dir / "lap.k").string() +
          " --units mm-t-s --out " + (dir / "out").string() + " 2>&1",
      status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("spot welds failed: 2\n  spotweld_1 at t = 2.77"), std::string::npos) << out;
  // and result.h5 keeps them (/events/spot_weld_failures), as the solver found them
  const auto welds = io::ResultReader((dir / "out" / "result.h5").string()).spot_weld_failures();
  ASSERT_EQ(welds.size(), 2u);
  EXPECT_EQ(welds[0].name, "spotweld_1");
  EXPECT_EQ(welds[1].name, "spotweld_2");
  EXPECT_EQ(welds[0].time_s, b.weld_failures()[0].time_s);
  EXPECT_EQ(welds[0].shear_N, b.weld_failures()[0].shear_N);
  EXPECT_EQ(welds[0].tension_N, b.weld_failures()[0].normal_N);
  std::filesystem::remove_all(dir);
}

// A checkpoint taken after the welds let go keeps them: the restored solver lists the same
// failures (the run's summary and result.h5 after a restart), and its welds stay released.
TEST(SpotWeld, FailuresSurviveARestart) {
  const model::Model m = lap_joint(2000.0);
  integration::Solver a(m);
  a.initialize();
  while (a.weld_failures().empty()) {
    a.begin_cycle();
    ASSERT_FALSE(a.finished()) << "the welds should let go before the end";
    a.end_cycle();
  }
  for (int k = 0; k < 10; ++k) {
    a.begin_cycle();
    a.end_cycle();
  }
  const auto path = std::filesystem::temp_directory_path() /
                    ("crashlink_weld_restart_" + std::to_string(::getpid()) + ".state.bin");
  core::StateWriter w;
  a.save_state(w);
  w.save(path.string());
  integration::Solver b(m);
  b.initialize();
  b.restore_state(core::StateReader(path.string()));
  std::filesystem::remove(path);
  ASSERT_EQ(b.weld_failures().size(), a.weld_failures().size());
  for (std::size_t k = 0; k < a.weld_failures().size(); ++k) {
    EXPECT_EQ(b.weld_failures()[k].name, a.weld_failures()[k].name);
    EXPECT_EQ(b.weld_failures()[k].time_s, a.weld_failures()[k].time_s);
    EXPECT_EQ(b.weld_failures()[k].shear_N, a.weld_failures()[k].shear_N);
  }
  testing::run_to_end(a);
  testing::run_to_end(b);
  EXPECT_EQ(a.displacement(), b.displacement());
  EXPECT_EQ(b.weld_failures().size(), a.weld_failures().size()) << "no weld fails twice";
}

}  // namespace
}  // namespace crashlink
