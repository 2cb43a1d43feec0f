// A keyword deck in split and multi through a scenario naming it (tests/data/decks/two_rates/:
// a steel bar held at one end and set moving at 1 m/s, 10 mm hexes on one half and 5 mm hexes
// on the other, cut into a `coarse` domain by PID and a `fine` one by title). As for the YAML
// scenes (split_mono_test.cpp, layer_network_test.cpp): split (cosim::LayerNetwork at a common
// step) equals mono at that step to round-off; multi (steps 2x apart) keeps the energy balance
// within 1 %; and `crashlink run two_rates.yaml --mode split|multi` runs the processes (exit 0).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/network_vs_mono.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

const std::string kScenario =
    std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/two_rates/two_rates.yaml";
const std::string kCrashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";

TEST(DeckDomains, SplitEqualsMonoAtTheCommonStep) {
  const model::Model global = io::read_scenario(kScenario);
  ASSERT_EQ(global.domains.size(), 2u);
  const auto r = testing::network_vs_mono(global, 0);
  const int cycles = static_cast<int>(global.controls.end_time_s / r.step_s) - 1;
  ASSERT_GT(cycles, 50);
  std::printf(
      "[measured] deck split vs mono: %d cycles, max |du| / max |u| = %.2e (max |u| %.3e m)\n",
      cycles, r.rel_diff, r.u_scale);
  EXPECT_GT(r.u_scale, 1e-6);  // the bar moved (1 m/s for 0.1 ms: up to 0.1 mm)
  EXPECT_LE(r.rel_diff, 1e-10);
}

TEST(DeckDomains, MultiAtStepsTwoApartKeepsTheEnergyBalance) {
  const model::Model global = io::read_scenario(kScenario);
  cosim::LayerNetworkOptions o;  // multi
  o.step_safety = 0.9;           // fixed steps: the margin `crashlink run` takes by default
  cosim::LayerNetwork net(global, o);
  net.initialize();
  const auto& n = net.plan().n;
  const auto substeps = std::max(n[0], n[1]) / std::min(n[0], n[1]);
  EXPECT_GE(substeps, 2) << "the 5 mm hexes step twice per step of the 10 mm ones";
  ASSERT_TRUE(net.run());
  const auto e = net.energy();
  const double e0 = e.initial_total_J;
  // 1 m/s on 78.5 g of steel (less the held end's share): about 39 mJ.
  EXPECT_GT(e0, 0.03);
  EXPECT_LT(e0, 0.04);
  EXPECT_GT(e.internal_J, 0.1 * e0);  // the wave turned kinetic energy into strain energy
  std::printf("[measured] deck multi: E0 %.4e J, balance %.3e J (%.4f %%), coupling work %.2e J\n",
              e0, e.balance_J(), 100.0 * e.balance_J() / e0, e.coupling_work_J);
  EXPECT_LT(std::abs(e.balance_J()) / e0, 0.01);
}

TEST(DeckDomains, CommandLineRunsTheScenarioInSplitAndMulti) {
  for (const std::string mode : {"split", "multi"}) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("crashlink_deck_domains_" + mode + "_" + std::to_string(::getpid()));
    const proc_test::RemoveIfPassed cleanup{dir};
    std::filesystem::remove_all(dir);
    int status = -1;
    const std::string out = testing::run_command(
        kCrashlink + " run " + kScenario + " --mode " + mode + " --quiet --out " + dir.string(),
        status);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << mode << "\n" << out;
    const auto at = out.find("energy balance error ");
    ASSERT_NE(at, std::string::npos) << out;
    const double pct = std::stod(out.substr(at + 21));
    EXPECT_LT(std::abs(pct), 1.0) << mode << "\n" << out;
    io::ResultReader r((dir / "result.h5").string());
    const auto tip = r.probe("tip");
    ASSERT_GT(tip.time_s.size(), 50u) << mode;
  }
}

TEST(DeckDomains, ADeckAloneInSplitOrMultiSaysHowToNameItsDomains) {
  const std::string deck =
      std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/two_rates/two_rates.k";
  int status = -1;
  const std::string out =
      testing::run_command(kCrashlink + " run " + deck + " --units mm-t-s --mode split", status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << out;
  EXPECT_NE(out.find("fix: write a scenario YAML that names the deck and its domains by *PART "
                     "PID or title, e.g."),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("model: {deck: two_rates.k, units: mm-t-s}"), std::string::npos) << out;
  EXPECT_NE(out.find("--mode split"), std::string::npos) << out;
}

}  // namespace
}  // namespace crashlink
