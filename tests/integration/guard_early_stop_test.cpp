// A guard stop within the first cycles is most likely a unit mistake in the input; its message
// says so (integration/guard.h early_stop_hint, issue 20 item 9c). Later stops do not.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>

#include "core/errors.h"
#include "solver/integration/guard.h"
#include "solver/io/scenario_reader.h"
#include "solver/run/run_single.h"

using namespace crashlink;

namespace {

const std::string kHint =
    "Stopped within the first 10 cycles: check the units of thickness, modulus, density, "
    "velocities (SI: m, Pa, kg/m^3, m/s).";

std::string balance_message(std::int64_t cycle) {
  model::Model m;
  m.nodes.id = {1};
  m.nodes.x0 = {0.0, 0.0, 0.0};
  integration::EnergyAccount e;
  e.kinetic_J = 2.0;  // from 1 J and no work: 100 % created
  e.initial_total_J = 1.0;
  e.update_reference();
  const double v[3] = {1.0, 0.0, 0.0};
  integration::GuardContext c;
  c.cycle = cycle;
  try {
    integration::check_energy_balance(m, e, {0.05, 0.0}, v, c);
  } catch (const NumericalError& err) {
    return err.what();
  }
  return "(no stop)";
}

std::string nan_message(std::int64_t cycle) {
  model::Model m;
  m.nodes.id = {1};
  m.nodes.x0 = {0.0, 0.0, 0.0};
  const double v[3] = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
  integration::GuardContext c;
  c.cycle = cycle;
  try {
    integration::check_finite_velocities(m, v, c);
  } catch (const NumericalError& err) {
    return err.what();
  }
  return "(no stop)";
}

}  // namespace

TEST(GuardEarlyStop, AStopInTheFirstCyclesNamesTheUnits) {
  for (std::int64_t cycle : {0, 5, 9}) {
    EXPECT_NE(balance_message(cycle).find(kHint), std::string::npos) << balance_message(cycle);
    EXPECT_NE(nan_message(cycle).find(kHint), std::string::npos) << nan_message(cycle);
  }
}

TEST(GuardEarlyStop, ALaterStopDoesNot) {
  for (std::int64_t cycle : {10, 500}) {
    EXPECT_NE(balance_message(cycle).find("Energy was created"), std::string::npos);
    EXPECT_EQ(balance_message(cycle).find("Stopped within"), std::string::npos);
    EXPECT_EQ(nan_message(cycle).find("Stopped within"), std::string::npos);
  }
}

// The mistake of the issue: a 10 mm shell plate 0.7 m thick (mm meant), let through the reader's
// check by its override, is stopped by the guard within the first cycles, with the hint.
TEST(GuardEarlyStop, AShellThicknessInMmIsStoppedWithTheHint) {
  const auto m = io::parse_scenario(R"(name: thick
controls:
  end_time: 1.0e-3
  plausibility_checks: false
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  plate:
    material: steel
    thickness: 0.7
    mesh: {generator: plate, size: [0.2, 0.2], divisions: [20, 20]}
boundary:
  - nodes: {box: {min: [0.0, 0.0, 0.0], max: [0.0, 0.2, 0.0]}}
    fix: all
initial_velocity:
  - nodes: {box: {min: [0.1, 0.0, 0.0], max: [0.2, 0.2, 0.0]}}
    velocity: [0.0, 0.0, 10.0]
)",
                                    "thick.yaml");
  run::RunOptions opt;
  opt.out_dir = (std::filesystem::temp_directory_path() / "crashlink_guard_thick_shell").string();
  opt.progress = false;
  const auto s = run::run_single_domain(m, opt);
  ASSERT_TRUE(s.failed) << "a 0.7 m thick shell of 10 mm ran to the end";
  EXPECT_LT(s.cycles, 10) << s.failure;
  EXPECT_NE(s.failure.find(kHint), std::string::npos) << s.failure;
}
