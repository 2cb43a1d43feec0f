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

std::string bar(const fs::path& dir, double end_time_s) {
  return crashlink::proc_test::write_file(
      dir / "bar.yaml",
      crashlink::proc_test::bar_parts_yaml("leftbar", end_time_s,
                                           {{"left", 0.0, 0.2, 20}, {"right", 0.2, 0.4, 10}}));
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
  const std::set<std::string> before = shm_files();
  std::vector<std::string> theirs;
  {
    Child run({bin("crashlink"), "run", bar(dir, 1.0), "--mode", "multi", "--quiet", "--out",
               (dir / "killed").string()});
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    while (std::chrono::steady_clock::now() < deadline) {
      theirs.clear();
      for (const auto& f : shm_files())
        if (!before.count(f)) theirs.push_back(f);
      if (theirs.size() >= 4) break;  // each domain's bell and ring
      ASSERT_FALSE(run.wait(20ms).has_value()) << run.output();
    }
    ASSERT_GE(theirs.size(), 4u) << run.output();
    run.signal(SIGKILL);  // the launcher; its pieces die with it (PR_SET_PDEATHSIG)
    ASSERT_TRUE(run.wait(10s).has_value());
  }
  std::this_thread::sleep_for(200ms);  // the pieces' own SIGKILL is delivered asynchronously
  for (const auto& f : theirs) EXPECT_TRUE(fs::exists(f)) << f << " removed by nobody?";

  int status = -1;
  const std::string out = run_command(bin("crashlink") + " run " + bar(dir, 2e-4) +
                                          " --mode multi --out " + (dir / "next").string(),
                                      status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("left by runs that were killed"), std::string::npos) << out;
  for (const auto& f : theirs) EXPECT_FALSE(fs::exists(f)) << f << " still there after a run";
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
