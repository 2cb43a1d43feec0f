// A keyword deck run in mono (tests/data/decks/cantilever.k: a hex bar held at one end and a
// shell strip held along an edge, both set moving at 1 m/s): the energy balance within 1 %,
// through the solver and through `crashlink run model.k --units mm-t-s`, whose input mistakes
// exit 2 (docs/processes.md "Exit codes").
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "solver/deck/model_from_deck.h"
#include "solver/integration/solver.h"
#include "solver/io/result_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

const std::string kDeck = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/cantilever.k";
const std::string kCrashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";

TEST(DeckRun, CantileverKeepsItsEnergyBalance) {
  const model::Model m = deck::read_deck(kDeck, {"mm-t-s", {}}).model;
  integration::Solver s(m);
  double e0 = 0.0, worst = 0.0, internal_max = 0.0;
  testing::run(s, [&](const integration::Solver& sv) {
    const auto& e = sv.energy();
    if (e0 == 0.0) e0 = e.total_J();
    worst = std::max(worst, std::abs(e.balance_J()));
    internal_max = std::max(internal_max, e.internal_J);
  });
  // 1 m/s on 78.5 g of bar and 3.9 g of strip: 41 mJ, less what the held nodes' share (5-9 %)
  // would carry; the bar's wave turns kinetic energy into strain energy and back.
  const double full = 0.5 * (7850.0 * 100e-9 * 10.0 * 10.0 + 7850.0 * 50e-9 * 10.0 * 1.0);
  EXPECT_GT(e0, 0.9 * full);
  EXPECT_LT(e0, 1.0000001 * full);
  EXPECT_GT(internal_max, 0.2 * e0);
  EXPECT_LT(worst / e0, 0.01) << "largest |balance| " << worst << " J of E0 " << e0 << " J";
}

TEST(DeckRun, CommandLineRunsADeckAndRefusesMistakesWithExit2) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("crashlink_deck_run_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  int status = 0;
  std::string out = testing::run_command(
      kCrashlink + " run " + kDeck + " --units mm-t-s --quiet --out " + dir.string(), status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  // *DATABASE_GLSTAT and _BINARY_D3PLOT set the output intervals: nothing is without effect.
  EXPECT_EQ(out.find("accepted without effect"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::exists(dir / "result.h5"));
  {
    // the deck's part ids in result.h5 (/mesh/parts/<name> attribute "id") and in the XDMF
    const io::ResultReader r((dir / "result.h5").string());
    const auto parts = r.mesh_parts();
    ASSERT_FALSE(parts.empty());
    const model::Model m = deck::read_deck(kDeck, {"mm-t-s", {}}).model;
    ASSERT_EQ(parts.size(), m.parts.size());
    for (std::size_t p = 0; p < parts.size(); ++p) {
      EXPECT_EQ(parts[p].name, m.parts[p].name);
      EXPECT_EQ(parts[p].id, m.parts[p].user_id);
      EXPECT_GT(parts[p].id, 0);
    }
    std::ifstream x(dir / "result.xdmf");
    const std::string xdmf((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
    EXPECT_NE(
        xdmf.find("<Grid Name=\"" + parts[0].name + " (PID " + std::to_string(parts[0].id) + ")\""),
        std::string::npos);
  }

  // Without --units: the one system its steel fits is inferred, and said.
  out =
      testing::run_command(kCrashlink + " run " + kDeck + " --quiet --out " + dir.string(), status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("crashlink run: deck: units: --units not given; read in mm-t-s"),
            std::string::npos)
      << out;
  // An unknown system is refused.
  out = testing::run_command(
      kCrashlink + " run " + kDeck + " --units mm-t-ms --out " + dir.string(), status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << out;
  EXPECT_NE(out.find(kDeck + ":0: --units: 'mm-t-ms' is not a known system"), std::string::npos)
      << out;

  out = testing::run_command(
      kCrashlink + " run " + kDeck + " --units mm-t-s --mode multi --out " + dir.string(), status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << out;
  EXPECT_NE(out.find("fix: write a scenario YAML that names the deck and its domains"),
            std::string::npos)
      << out;
  std::filesystem::remove_all(dir);
}

// `crashlink advise` on a deck: the steps per part, the best split, and the scenario to write
// around the deck (model line, domains by title, or by PID for a part without one).
TEST(DeckRun, AdvisePrintsTheScenarioToWrite) {
  const std::string two_rates =
      std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/two_rates/two_rates.k";
  int status = 0;
  std::string out = testing::run_command(kCrashlink + " advise " + two_rates, status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("crashlink advise: deck: units: --units not given; read in mm-t-s"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("model: {deck: " + two_rates +
                     ", units: mm-t-s}\ndomains:\n  fine: {parts: [fine]}\n  coarse: {parts: "
                     "[coarse]}\n"),
            std::string::npos)
      << out;
  // the same deck with the fine part's title blank: named by its PID
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_advise_deck_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::copy(
      std::filesystem::path(two_rates).parent_path(), dir,
      std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  {
    std::ifstream in(dir / "two_rates.k");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("*PART\nfine\n");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 11, "*PART\n\n");
    std::ofstream(dir / "two_rates.k") << text;
  }
  out = testing::run_command(kCrashlink + " advise " + (dir / "two_rates.k").string(), status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("  fine: {parts: [2]}\n  coarse: {parts: [coarse]}\n"), std::string::npos)
      << out;
  // --process-sample times a scenario's own domains: refused on a deck
  out = testing::run_command(kCrashlink + " advise " + two_rates + " --process-sample 0.1", status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << out;
  EXPECT_NE(out.find("--process-sample: times the scenario's own domains, which a deck does not "
                     "name"),
            std::string::npos)
      << out;
  std::filesystem::remove_all(dir);
}

// A deck's restart fingerprint covers its includes: a checkpointed run of the two-rate deck (its
// nodes in an *INCLUDE) restarts as it is, and is refused once the included file changed.
TEST(DeckRun, RestartIsRefusedWhenAnIncludedFileChanged) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_deck_restart_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto src = std::filesystem::path(CRASHLINK_TEST_DATA_DIR) / "data/decks/two_rates";
  for (const char* f : {"two_rates.k", "bar_nodes.k"}) std::filesystem::copy_file(src / f, dir / f);
  const std::string deck = (dir / "two_rates.k").string(), out = (dir / "out").string();
  int status = 0;
  std::string text = testing::run_command(
      kCrashlink + " run " + deck + " --quiet --checkpoint-interval 2e-5 --out " + out, status);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  text = testing::run_command(kCrashlink + " run " + deck + " --quiet --restart " + out, status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  {  // one byte of the included file: a comment line
    std::ofstream(dir / "bar_nodes.k", std::ios::app) << "$ changed\n";
  }
  text = testing::run_command(kCrashlink + " run " + deck + " --quiet --restart " + out, status);
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  EXPECT_NE(text.find("restart with the scenario file and the --mode that wrote it"),
            std::string::npos)
      << text;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace crashlink
