// What a run leaves behind (issue 20 item 12): an ipc run removes its socket and endpoint file
// from the output folder, and the shared-memory rings in /dev/shm that a SIGKILLed run could not
// remove are removed by the next run's coordinator. Before: coordinator.sock and
// coordinator.endpoint stayed after every ipc run, and a killed launcher left 8.4 MB of rings
// until a rerun in the same folder.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using crashlink::proc_test::bin;
using crashlink::proc_test::Child;
using crashlink::proc_test::fresh_dir;
using crashlink::testing::run_command;

std::set<std::string> shm_files() {
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/dev/shm", ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("crashlink-", 0) == 0) names.insert(e.path().string());
  }
  return names;
}

// Domain names no other test uses: the rings of this test's runs are the /dev/shm files named
// after them (other tests' runs come and go in /dev/shm meanwhile, under ctest -j2).
std::string bar(const fs::path& dir, double end_time_s) {
  return crashlink::proc_test::write_file(
      dir / "bar.yaml",
      crashlink::proc_test::bar_parts_yaml(
          "leftbar", end_time_s, {{"leftover1", 0.0, 0.2, 20}, {"leftover2", 0.2, 0.4, 10}}));
}

bool ours(const std::string& path) {
  return (path.find(".leftover1.") != std::string::npos ||
          path.find(".leftover2.") != std::string::npos) &&
         path.find(".tmp") == std::string::npos && path.find(".orphan") == std::string::npos;
}

TEST(Leftovers, AnIpcRunRemovesItsSocketAndEndpointFile) {
  const fs::path dir = fresh_dir("left_sock");
  int status = -1;
  const std::string out = run_command(bin("crashlink") + " run " + bar(dir, 2e-4) +
                                          " --mode multi --quiet --out " + (dir / "out").string(),
                                      status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_TRUE(fs::exists(dir / "out" / "result.h5"));
  EXPECT_FALSE(fs::exists(dir / "out" / "coordinator.sock")) << out;
  EXPECT_FALSE(fs::exists(dir / "out" / "coordinator.endpoint")) << out;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

TEST(Leftovers, RingsOfAKilledRunAreRemovedByTheNextRun) {
  if (!fs::is_directory("/dev/shm")) GTEST_SKIP() << "no /dev/shm: lanes are files in OUT";
  const fs::path dir = fresh_dir("left_shm");
  std::vector<std::string> theirs;
  {
    Child run({bin("crashlink"), "run", bar(dir, 1.0), "--mode", "multi", "--quiet", "--out",
               (dir / "killed").string()});
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    while (std::chrono::steady_clock::now() < deadline) {
      theirs.clear();
      for (const auto& f : shm_files())
        if (ours(f)) theirs.push_back(f);
      if (theirs.size() >= 4) break;  // each domain's bell and ring
      ASSERT_FALSE(run.wait(20ms).has_value()) << run.output();
    }
    ASSERT_GE(theirs.size(), 4u) << run.output();
    run.signal(SIGKILL);  // the launcher; its pieces die with it (PR_SET_PDEATHSIG)
    ASSERT_TRUE(run.wait(10s).has_value());
  }
  // (another test's coordinator starting meanwhile may reclaim them first: only their absence
  // after the next run is checked)

  int status = -1;
  const std::string out = run_command(bin("crashlink") + " run " + bar(dir, 2e-4) +
                                          " --mode multi --out " + (dir / "next").string(),
                                      status);
  ASSERT_EQ(status, 0) << out;
  for (const auto& f : theirs) EXPECT_FALSE(fs::exists(f)) << f << " still there after a run";
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
