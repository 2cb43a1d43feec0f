// Messages that misled (issue 20 item 11): a domain that the layer cut empties is named as such
// (not "give the scenario a `domains:` section" to a scenario that has one); `compare` refuses a
// swapped pair and two different models instead of printing "121.4 % of ideal" with exit 0; the
// coupling work of a driven model is a share of the external work, not of an initial energy of 0.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <string>
#include <tuple>

#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using crashlink::proc_test::bin;
using crashlink::proc_test::fresh_dir;
using crashlink::testing::run_command;

int code_of(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CliMessages, ADomainTheLayerCutEmptiesIsNamed) {
  const fs::path dir = fresh_dir("msg_empty");
  // `coarse` is one element long: the fine side takes that layer, and with it the whole domain
  const std::string scenario = crashlink::proc_test::write_file(
      dir / "empty.yaml", crashlink::proc_test::bar_parts_yaml(
                              "emptycut", 1e-4, {{"fine", 0.0, 0.2, 20}, {"coarse", 0.2, 0.4, 1}}));
  int status = -1;
  const std::string out = run_command(
      bin("crashlink") + " run " + scenario + " --mode multi --out " + (dir / "o").string(),
      status);
  EXPECT_EQ(code_of(status), 2) << out;
  EXPECT_NE(out.find("leaves domain(s) 'coarse' empty"), std::string::npos) << out;
  EXPECT_EQ(out.find("give the scenario a `domains:` section"), std::string::npos) << out;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

TEST(CliMessages, CompareRefusesASwappedPairAndAnotherModel) {
  const fs::path dir = fresh_dir("msg_compare");
  const std::string bar = crashlink::proc_test::write_file(
      dir / "bar.yaml", crashlink::proc_test::bar_parts_yaml(
                            "cmpbar", 2e-4, {{"fine", 0.0, 0.2, 20}, {"coarse", 0.2, 0.4, 10}}));
  const std::string other = crashlink::proc_test::write_file(
      dir / "other.yaml", crashlink::proc_test::bar_parts_yaml(
                              "cmpbar", 2e-4, {{"fine", 0.0, 0.2, 10}, {"coarse", 0.2, 0.4, 10}}));
  int status = -1;
  for (const auto& [yaml, mode, out] :
       {std::tuple{bar, "mono", "mono"}, std::tuple{bar, "multi", "multi"},
        std::tuple{other, "mono", "other"}}) {
    const std::string log = run_command(bin("crashlink") + " run " + yaml + " --quiet --mode " +
                                            mode + " --out " + (dir / out).string(),
                                        status);
    ASSERT_EQ(code_of(status), 0) << log;
  }
  const auto h5 = [&](const char* run) {
    std::string arg(1, ' ');
    arg += (dir / run / "result.h5").string();
    return arg;
  };
  const std::string fine =
      run_command(bin("crashlink") + " compare" + h5("mono") + h5("multi"), status);
  EXPECT_EQ(code_of(status), 0) << fine;
  // the coupling work of this load-driven bar (initial energy 0) is a share of its external work
  const std::string multi_log = run_command(
      bin("crashlink") + " run " + bar + " --quiet --mode multi --out " + (dir / "multi2").string(),
      status);
  EXPECT_NE(multi_log.find("of the external work)"), std::string::npos) << multi_log;

  const std::string swapped =
      run_command(bin("crashlink") + " compare" + h5("multi") + h5("mono"), status);
  EXPECT_EQ(code_of(status), 2) << swapped;
  EXPECT_NE(swapped.find("swap them"), std::string::npos) << swapped;
  const std::string models =
      run_command(bin("crashlink") + " compare" + h5("other") + h5("multi"), status);
  EXPECT_EQ(code_of(status), 2) << models;
  EXPECT_NE(models.find("are not runs of the same model"), std::string::npos) << models;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace

// The run's configuration is checked once, before anything starts (coordinator::validate, issue
// 23): a scheme's own rule refuses the run with exit 2 and its fix, from `crashlink run` and from
// `crashlink-coordinator` alike, and no process of the run is started (no domains/ folder).
TEST(CliMessages, ASchemesOwnRuleRefusesTheRunBeforeItStarts) {
  const fs::path dir = fresh_dir("msg_config");
  const std::string bar = crashlink::proc_test::write_file(
      dir / "bar.yaml", crashlink::proc_test::bar_parts_yaml(
                            "cfgbar", 1e-4, {{"fine", 0.0, 0.2, 20}, {"coarse", 0.2, 0.4, 10}}));
  int status = -1;
  const struct {
    std::string args;
    std::string said;
  } cases[] = {
      {"--mode multi --coupling paper --checkpoint-interval 1e-5",
       "--coupling paper: checkpoints and --restart are features of `layer` runs"},
      {"--mode multi --no-drift", "--no-drift: a `paper` option; `layer` has no drift correction"},
  };
  for (const auto& c : cases) {
    const fs::path out = dir / "o";
    const std::string log = run_command(
        bin("crashlink") + " run " + bar + " --quiet " + c.args + " --out " + out.string(), status);
    EXPECT_EQ(code_of(status), 2) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.said), std::string::npos) << c.args << "\n" << log;
    EXPECT_FALSE(fs::exists(out / "domains")) << c.args << ": a piece of the run started";
  }
  const std::string log =
      run_command(bin("crashlink-coordinator") + " --bind tcp://127.0.0.1:0 --scenario " + bar +
                      " --out " + (dir / "c").string() + " --coupling paper --restart",
                  status);
  EXPECT_EQ(code_of(status), 2) << log;
  EXPECT_NE(log.find("features of `layer` runs"), std::string::npos) << log;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}
