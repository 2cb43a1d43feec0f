// Solver::save_state / restore_state (solver_state.cpp): a solver restored from a checkpoint taken
// mid-run, with the headform in contact with the plate (rigid body, shells with plasticity,
// contact history and candidates), ends in the same state as the solver that went on, to the bit.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"

namespace {

using crashlink::integration::Solver;

struct End {
  std::vector<double> u, v, a;
  double total_J = 0.0, contact_J = 0.0, internal_J = 0.0, time_s = 0.0;
  std::int64_t cycle = 0;
  double head_v = 0.0;
};

End run_to_end(Solver& s) {
  for (;;) {
    s.begin_cycle();
    if (s.finished()) break;
    s.end_cycle();
  }
  End e;
  e.u = s.displacement();
  e.v = s.velocity_mid();
  e.a = s.acceleration();
  e.total_J = s.energy().total_J();
  e.contact_J = s.energy().contact_J;
  e.internal_J = s.energy().internal_J;
  e.time_s = s.time_s();
  e.cycle = s.cycle();
  e.head_v = s.rigid_bodies().at(0).velocity[2];
  return e;
}

/// One file per test and process: ctest runs this file's tests as separate processes, side by
/// side with -j2, and a shared file let one test restore another's checkpoint (seen once in a CI
/// dry run: cycle 0 restored where 2045 was saved).
std::string checkpoint_path() {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_solver_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  return (dir / fmt::format("{}.{}.state.bin", test, ::getpid())).string();
}

void restored_solver_ends_bit_identical(bool global_step) {
  auto model = crashlink::io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) +
                                            "/scenarios/plate_impact_small.yaml");
  model.controls.global_stable_step = global_step;
  Solver a(model);
  a.initialize();
  const double t_save = 0.6 * model.controls.end_time_s;  // the headform is on the plate
  for (;;) {
    a.begin_cycle();
    a.end_cycle();
    if (a.time_s() >= t_save) break;
  }
  ASSERT_GT(a.energy().contact_J, 0.0) << "the checkpoint should be taken during contact";
  crashlink::core::StateWriter w;
  a.save_state(w);
  w.save(checkpoint_path());
  const std::int64_t saved_cycle = a.cycle();
  const End went_on = run_to_end(a);

  Solver b(model);
  b.initialize();
  b.restore_state(crashlink::core::StateReader(checkpoint_path()));
  EXPECT_EQ(b.cycle(), saved_cycle);
  const End restored = run_to_end(b);

  EXPECT_EQ(restored.cycle, went_on.cycle);
  EXPECT_EQ(restored.time_s, went_on.time_s);
  EXPECT_EQ(restored.u, went_on.u);  // to the bit: every double equal
  EXPECT_EQ(restored.v, went_on.v);
  EXPECT_EQ(restored.a, went_on.a);
  EXPECT_EQ(restored.total_J, went_on.total_J);
  EXPECT_EQ(restored.contact_J, went_on.contact_J);
  EXPECT_EQ(restored.internal_J, went_on.internal_J);
  EXPECT_EQ(restored.head_v, went_on.head_v);
  // and the run did change after the checkpoint (the comparison is not of two frozen states)
  EXPECT_GT(went_on.cycle, saved_cycle + 10);
}

TEST(SolverCheckpoint, RestoredSolverEndsBitIdenticalToTheOneThatWentOn) {
  restored_solver_ends_bit_identical(false);
}

// The global stable step's Lanczos vector, reference element steps and refresh cycle are part of
// the state: without them the restored run refreshes at other cycles and takes other steps.
TEST(SolverCheckpoint, GlobalStableStepIsRestored) {
  restored_solver_ends_bit_identical(true);
}

// Coupling loads (Solver::add_coupling_force, as a coupled domain receives them) live only on the
// nodes that were given one (solver.h coupled_); a checkpoint taken after the accelerations
// and before the next positions still holds them (their F^n half of the work is not yet counted)
// and the restored solver must find them again: same bits to the end, coupling work included.
TEST(SolverCheckpoint, PendingCouplingLoadsAreRestored) {
  const auto model = crashlink::io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) +
                                                  "/scenarios/plate_impact_small.yaml");
  const std::size_t node = model.nodes.count() / 2;
  auto cycle = [node](Solver& s) {
    s.begin_cycle();
    s.end_cycle_forces();
    const double f = 50.0 * std::sin(1e4 * s.time_s());  // N
    s.add_coupling_force(node, {0.0, 0.0, f});
    s.end_cycle_accelerations();
  };
  Solver a(model);
  a.initialize();
  ASSERT_GT(a.mass()[node], 0.0);
  for (int k = 0; k < 200; ++k) cycle(a);
  crashlink::core::StateWriter w;
  a.save_state(w);
  w.save(checkpoint_path());
  Solver b(model);
  b.initialize();
  b.restore_state(crashlink::core::StateReader(checkpoint_path()));
  for (int k = 0; k < 300; ++k) {
    cycle(a);
    cycle(b);
  }
  EXPECT_NE(a.energy().coupling_work_J, 0.0) << "the loads should have done work";
  EXPECT_EQ(b.energy().coupling_work_J, a.energy().coupling_work_J);
  EXPECT_EQ(b.displacement(), a.displacement());
  EXPECT_EQ(b.velocity_mid(), a.velocity_mid());
  EXPECT_EQ(b.acceleration(), a.acceleration());
}

TEST(SolverCheckpoint, CheckpointOfAnotherModelIsRefused) {
  const auto plate = crashlink::io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) +
                                                  "/scenarios/plate_impact_small.yaml");
  const auto bar =
      crashlink::io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/bar_wave.yaml");
  Solver a(plate);
  a.initialize();
  crashlink::core::StateWriter w;
  a.save_state(w);
  w.save(checkpoint_path());
  Solver b(bar);
  b.initialize();
  try {
    b.restore_state(crashlink::core::StateReader(checkpoint_path()));
    FAIL() << "restored a plate checkpoint into a bar";
  } catch (const crashlink::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes"), std::string::npos) << e.what();
  }
}

}  // namespace
