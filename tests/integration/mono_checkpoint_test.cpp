// Checkpoints and restart of a mono run (issue 20 item 11, docs/checkpoints.md "mono"): the CI
// head-impact scene (shells, hexes, contacts, a rigid headform) in one process with a checkpoint
// every 2 ms, SIGKILLed between two checkpoints, then resumed with `crashlink run --mode mono
// --restart DIR`: the resumed result.h5 equals the one of the run without checkpoints to the bit.
// Before, mono ignored --checkpoint-interval (no checkpoint written, the run went to its end) and
// refused --restart. Also: a damaged newest checkpoint falls back to the previous one, and the
// refusals (exit 2, with the fix) of a folder without checkpoints, of another scenario's, and of a
// coupled run's checkpoints given to mono or the reverse.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "core/exit_codes.h"
#include "solver/run/checkpoint_store.h"
#include "solver/run/run_single.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/result_compare.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using crashlink::proc_test::bin;
using crashlink::proc_test::Child;
using crashlink::proc_test::exit_code;
using crashlink::proc_test::fresh_dir;
using crashlink::proc_test::RemoveIfPassed;
using crashlink::testing::expect_same_results;
using crashlink::testing::run_command;

const std::string kScenario =
    std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml";
const std::string kPiece = crashlink::run::RunOptions().domain_name;  // the mono run's domain
const std::string kMarker = "restarted from the checkpoint at t = ";

std::string mono(const std::string& scenario, const std::string& args) {
  return bin("crashlink") + " run " + scenario + " --mode mono --quiet " + args;
}

TEST(MonoCheckpointRestart, KilledRunResumedEqualsUninterruptedRun) {
  const fs::path dir = fresh_dir("mono_ckpt");
  RemoveIfPassed cleanup{dir};
  int status = -1;
  const std::string out_ref =
      run_command(mono(kScenario, "--out " + (dir / "ref").string()), status);
  ASSERT_EQ(status, 0) << out_ref;

  // With checkpoints every 2 ms, killed between the second and the third.
  const fs::path killed = dir / "killed";
  {
    Child run({bin("crashlink"), "run", kScenario, "--mode", "mono", "--quiet",
               "--checkpoint-interval", "0.002", "--out", killed.string()});
    const auto deadline = std::chrono::steady_clock::now() + 300s;
    while (crashlink::run::list_checkpoints(killed.string(), kPiece).size() < 2 &&
           std::chrono::steady_clock::now() < deadline) {
      ASSERT_FALSE(run.wait(20ms).has_value())
          << "finished without its second checkpoint, so it could not be killed after it:\n"
          << run.output();
    }
    ASSERT_FALSE(run.wait(200ms).has_value()) << run.output();  // into the next interval
    run.signal(SIGKILL);
    ASSERT_TRUE(run.wait(10s).has_value());
    EXPECT_NE(run.output().find("crashlink: mono: checkpoint at t = "), std::string::npos)
        << run.output();
  }
  const auto left = crashlink::run::list_checkpoints(killed.string(), kPiece);
  ASSERT_GE(left.size(), 2u);
  ASSERT_LE(left.size(), 3u);  // the newest 3 kept

  const std::string out = run_command(
      mono(kScenario, "--checkpoint-interval 0.002 --restart " + killed.string()), status);
  ASSERT_EQ(status, 0) << out;
  const auto at = out.find(kMarker);
  ASSERT_NE(at, std::string::npos) << out;
  const double restart_s = std::stod(out.substr(at + kMarker.size()));
  std::printf("[measured] mono: %zu checkpoints on disk at the kill, restarted from %.4f ms\n",
              left.size(), 1e3 * restart_s);
  EXPECT_GE(restart_s, 0.004);  // at or after the second multiple
  expect_same_results((dir / "ref" / "result.h5").string(), (killed / "result.h5").string());
}

// A small bar: a mono run with checkpoints every 1e-4 s (5 over 6e-4 s, the newest 3 kept), one
// byte flipped in the newest one's copy of result.h5. The restart says so, falls back to the
// previous one, and ends with the bits of the run without checkpoints.
TEST(MonoCheckpointRestart, ADamagedNewestCheckpointIsReportedAndThePreviousOneUsed) {
  const fs::path dir = fresh_dir("mono_ckpt_damaged");
  RemoveIfPassed cleanup{dir};
  const std::string scenario =
      crashlink::proc_test::write_file(dir / "bar.yaml", crashlink::proc_test::bar_yaml(6.0e-4));
  int status = -1;
  const std::string out_ref =
      run_command(mono(scenario, "--out " + (dir / "ref").string()), status);
  ASSERT_EQ(status, 0) << out_ref;
  const fs::path ck = dir / "ck";
  const std::string out_ck =
      run_command(mono(scenario, "--checkpoint-interval 1e-4 --out " + ck.string()), status);
  ASSERT_EQ(status, 0) << out_ck;
  expect_same_results((dir / "ref" / "result.h5").string(), (ck / "result.h5").string(), 2);
  const auto instants = crashlink::run::list_checkpoints(ck.string(), kPiece);
  ASSERT_EQ(instants.size(), 3u) << out_ck;
  const fs::path copy =
      fs::path(crashlink::run::checkpoint_folder(ck.string(), instants.back(), kPiece)) /
      "result.h5";
  ASSERT_TRUE(fs::exists(copy));
  crashlink::proc_test::flip_middle_byte(copy);
  const std::string out = run_command(mono(scenario, "--restart " + ck.string()), status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("checkpoint damaged, not used"), std::string::npos) << out;
  EXPECT_NE(out.find("result.h5: FNV-1a"), std::string::npos) << out;
  EXPECT_NE(out.find("is damaged: falling back"), std::string::npos) << out;
  const auto at = out.find(kMarker);
  ASSERT_NE(at, std::string::npos) << out;
  const double from_s = std::stod(out.substr(at + kMarker.size()));
  EXPECT_LT(from_s, 1e-15 * static_cast<double>(instants.back()));
  EXPECT_GE(from_s, 1e-15 * static_cast<double>(instants[1]) * (1.0 - 1e-9));
  expect_same_results((dir / "ref" / "result.h5").string(), (ck / "result.h5").string(), 2);
}

/// Exit 2 and every piece of `expect` in the output.
void expect_refused(const std::string& command, const std::vector<std::string>& expect) {
  int status = -1;
  const std::string out = run_command(command, status);
  EXPECT_EQ(exit_code(status), crashlink::kExitInput) << out;
  for (const auto& e : expect) EXPECT_NE(out.find(e), std::string::npos) << e << "\n" << out;
}

TEST(MonoCheckpointRefusals, NoCheckpointAnotherScenarioAndAnotherModeAreRefused) {
  const fs::path dir = fresh_dir("mono_ckpt_refused");
  RemoveIfPassed cleanup{dir};
  const std::string bar = crashlink::proc_test::bar_yaml(3.0e-4);
  const std::string scenario = crashlink::proc_test::write_file(dir / "bar.yaml", bar);
  const std::string other = crashlink::proc_test::write_file(
      dir / "other.yaml", crashlink::proc_test::bar_yaml(3.0e-4, "bar2_other"));

  // no checkpoint: refused, and the folder left as it was (no result file opened)
  const fs::path empty = dir / "empty";
  fs::create_directories(empty);
  expect_refused(mono(scenario, "--restart " + empty.string()),
                 {"no intact checkpoint of a mono run", "run from the start without --restart"});
  EXPECT_FALSE(fs::exists(empty / "result.h5"));

  // another scenario's checkpoints
  const fs::path m = dir / "mono";
  int status = -1;
  const std::string out_m =
      run_command(mono(scenario, "--checkpoint-interval 1e-4 --out " + m.string()), status);
  ASSERT_EQ(status, 0) << out_m;
  ASSERT_FALSE(crashlink::run::list_checkpoints(m.string(), kPiece).empty()) << out_m;
  const auto before = fs::last_write_time(m / "result.h5");
  expect_refused(mono(other, "--restart " + m.string()),
                 {"of scenario", "restart with the scenario file and the --mode that wrote it"});
  EXPECT_EQ(fs::last_write_time(m / "result.h5"), before);

  // a mono run's checkpoints given to a coupled restart
  expect_refused(
      bin("crashlink") + " run " + scenario + " --mode multi --quiet --restart " + m.string(),
      {"checkpoints are a mono run's", "restart it with --mode mono"});

  // a coupled run's checkpoints given to mono
  const fs::path c = dir / "multi";
  const std::string out_c = run_command(bin("crashlink") + " run " + scenario +
                                            " --mode multi --quiet --checkpoint-interval 1e-4 "
                                            "--out " +
                                            c.string(),
                                        status);
  ASSERT_EQ(status, 0) << out_c;
  ASSERT_FALSE(crashlink::run::list_checkpoints(c.string(), "fine").empty()) << out_c;
  expect_refused(mono(scenario, "--restart " + c.string()),
                 {"checkpoints are a coupled run's (pieces coarse, coordinator, fine)",
                  "restart it with the --mode (split or multi) that wrote them"});
}

}  // namespace
