// Issue 24 item 1 over the programs: `crashlink run --threads N` gives the run of one thread to the
// bit (histories, probes, contacts, field states), in mono and with every daemon of a coupled run
// on N threads (multi over ipc, split), on the CI head-impact scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/integration/process_test_support.h"
#include "tests/integration/result_compare.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using crashlink::proc_test::bin;
using crashlink::proc_test::fresh_dir;

const std::string kScenario =
    std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml";

/// Runs the scene with `mode` and `threads` into a fresh folder; returns its result.h5.
std::string run(const std::string& mode, int threads) {
  const fs::path out = fresh_dir("threads_" + mode + "_" + std::to_string(threads));
  int status = -1;
  const std::string log = crashlink::testing::run_command(
      bin("crashlink") + " run " + kScenario + " --mode " + mode + " --quiet --threads " +
          std::to_string(threads) + " --out " + out.string(),
      status);
  EXPECT_EQ(status, 0) << log;
  return (out / "result.h5").string();
}

}  // namespace

TEST(ThreadsOverProcesses, MonoOn3ThreadsIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("mono", 1), run("mono", 3));
}

TEST(ThreadsOverProcesses, MultiWith2ThreadsPerDaemonIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("multi", 1), run("multi", 2));
}

TEST(ThreadsOverProcesses, SplitWith2ThreadsPerDaemonIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("split", 1), run("split", 2));
}
