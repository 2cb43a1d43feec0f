// Checkpoint and restart of a coupled run over processes (issue #6 item 5, docs/design.md §2.6
// "Checkpoints"): the CI head-impact scene (wiper and body domains, links and contacts across
// them, shells, hexes, a rigid headform) run in `multi` with checkpoints every 2 ms; the same run
// SIGKILLed (the launcher, hence every process: PR_SET_PDEATHSIG) between its second and third
// checkpoints, then resumed with `crashlink run --restart DIR`. The resumed result.h5 equals the
// uninterrupted one to the bit (histories, coupling histories, field states), and the restart
// lost at most one checkpoint interval of simulated time.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "solver/io/result_reader.h"
#include "solver/run/checkpoint_store.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/result_compare.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using crashlink::proc_test::bin;
using crashlink::proc_test::Child;
using crashlink::proc_test::fresh_dir;
using crashlink::testing::expect_same_results;
using crashlink::testing::run_command;

const std::string kScenario =
    std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml";
constexpr double kInterval_s = 0.002;

std::string run_line(const fs::path& out, const std::string& extra) {
  return bin("crashlink") + " run " + kScenario + " --mode multi --quiet --checkpoint-interval " +
         std::to_string(kInterval_s) + " " + extra + " --out " + out.string();
}

std::size_t complete_instants(const fs::path& out) {
  const auto c = crashlink::run::list_checkpoints(out.string(), "coordinator");
  std::size_t n = 0;
  for (const auto t : c) {
    const bool all = fs::exists(crashlink::run::checkpoint_folder(out.string(), t, "wiper")) &&
                     fs::exists(crashlink::run::checkpoint_folder(out.string(), t, "body"));
    n += all ? 1 : 0;
  }
  return n;
}

/// The latest time any domain file of a killed run had on disk (its flushed history rows).
double time_reached(const fs::path& out) {
  double t = 0.0;
  for (const char* d : {"wiper", "body"}) {
    try {
      const crashlink::io::ResultReader r((out / "domains" / (std::string(d) + ".h5")).string());
      const auto g = r.glstat();
      if (!g.empty()) t = std::max(t, g.back().time_s);
    } catch (const std::exception&) {
      // a file killed mid-write: the checkpoints are what a restart uses
    }
  }
  return t;
}

/// The chain fine | mid | coarse (5 / 10 / 30 mm hexes), 0.6 ms, written into `dir`.
std::string chain3_scenario(const fs::path& dir) {
  return crashlink::proc_test::write_file(
      dir / "chain.yaml",
      crashlink::proc_test::bar_parts_yaml(
          "chain3", 6.0e-4,
          {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}}));
}

/// Fixed steps, and variable ones (each domain its own proposal; the checkpoints at the body's
/// first instant at or after each multiple of the interval, where the wiper pauses with it).
class CheckpointRestart : public ::testing::TestWithParam<std::string> {};

std::string steps_name(const ::testing::TestParamInfo<std::string>& p) {
  return p.param.empty() ? "Fixed" : "Variable";
}

INSTANTIATE_TEST_SUITE_P(Steps, CheckpointRestart,
                         ::testing::Values(std::string(), std::string("--variable-steps")),
                         steps_name);

TEST_P(CheckpointRestart, KilledRunResumedEqualsUninterruptedRun) {
  const std::string steps = GetParam();
  const std::string tag = steps.empty() ? "" : "_var";
  const fs::path ref = fresh_dir("ckpt_ref" + tag);
  int status = -1;
  const std::string out_ref = run_command(run_line(ref, steps), status);
  ASSERT_EQ(status, 0) << out_ref;
  EXPECT_GE(complete_instants(ref), 3u) << out_ref;  // 3 kept (6, 8, 10 ms)
  if (!steps.empty()) {
    // at instants of the leader: not the multiples of the interval to the tick
    for (const auto t : crashlink::run::list_checkpoints(ref.string(), "coordinator"))
      std::printf("[measured] variable steps: a checkpoint at %lld ticks\n",
                  static_cast<long long>(t));
  }

  // The same run, killed between its second and third checkpoints.
  const fs::path dir = fresh_dir("ckpt_killed" + tag);
  {
    std::vector<std::string> argv{bin("crashlink"),
                                  "run",
                                  kScenario,
                                  "--mode",
                                  "multi",
                                  "--quiet",
                                  "--checkpoint-interval",
                                  std::to_string(kInterval_s),
                                  "--out",
                                  dir.string()};
    if (!steps.empty()) argv.push_back(steps);
    Child run(argv);
    const auto deadline = std::chrono::steady_clock::now() + 300s;
    while (complete_instants(dir) < 2 && std::chrono::steady_clock::now() < deadline) {
      ASSERT_FALSE(run.wait(20ms).has_value()) << "finished before it could be killed:\n"
                                               << run.output();
    }
    // Into the next interval (about 0.6 ms of simulated time here); wherever the kill lands
    // before the end, the checks below hold.
    ASSERT_FALSE(run.wait(300ms).has_value()) << run.output();
    ASSERT_GE(complete_instants(dir), 2u) << run.output();
    run.signal(SIGKILL);  // the launcher; its pieces die with it (PR_SET_PDEATHSIG)
    ASSERT_TRUE(run.wait(10s).has_value());
  }
  std::this_thread::sleep_for(200ms);  // the pieces' own SIGKILL is delivered asynchronously
  const double reached_s = time_reached(dir);
  ASSERT_FALSE(fs::exists(dir / "result.h5"));

  const std::string out = run_command(
      bin("crashlink") + " run " + kScenario + " --mode multi --quiet --checkpoint-interval " +
          std::to_string(kInterval_s) + " " + steps + " --restart " + dir.string(),
      status);
  ASSERT_EQ(status, 0) << out;
  const std::string marker = "from the checkpoint at t = ";
  const auto at = out.find(marker);
  ASSERT_NE(at, std::string::npos) << out;
  const double restart_s = std::stod(out.substr(at + marker.size()));
  std::printf("[measured] killed with %.4f ms on disk, restarted from %.4f ms (interval %.4f ms)\n",
              1e3 * reached_s, 1e3 * restart_s, 1e3 * kInterval_s);
  EXPECT_GT(restart_s, 0.0);
  // At most one interval of simulated time lost (+1 % for the interval's rounding to steps).
  EXPECT_GE(restart_s, reached_s - 1.01 * kInterval_s);

  expect_same_results((ref / "result.h5").string(), (dir / "result.h5").string());
}

// Variable steps on a chain fine | mid | coarse, over processes: mid follows coarse and leads
// fine, so the three pause together only if each owner's u_J says where (LayerMessage::pause).
// The run with checkpoints, resumed from its newest, ends as the run without them, to the bit.
TEST(CheckpointRestartChain, VariableStepsRestartedFromTheNewestCheckpointIsTheSameRun) {
  const fs::path dir = fresh_dir("ckpt_chain");
  const std::string scenario = chain3_scenario(dir);
  const std::string run = bin("crashlink") + " run " + scenario +
                          " --mode multi --quiet --variable-steps --step-safety 0.8 ";
  int status = -1;
  const std::string out_ref = run_command(run + "--out " + (dir / "ref").string(), status);
  ASSERT_EQ(status, 0) << out_ref;
  // 1.1e-4 s: 5 checkpoints, the newest 3 kept; 2e-6 s, less than one coarse step (about 2.6 us):
  // one at nearly every instant of the leader, each pause straight after the one before
  for (const std::string interval : {"1.1e-4", "2e-6"}) {
    const std::string every = "--checkpoint-interval " + interval + " ";
    const fs::path ck = dir / ("ck" + interval);
    const std::string out_ck = run_command(run + every + "--out " + ck.string(), status);
    ASSERT_EQ(status, 0) << out_ck;
    const auto instants = crashlink::run::list_checkpoints(ck.string(), "coordinator");
    ASSERT_EQ(instants.size(), 3u) << out_ck;  // the newest 3
    for (const char* d : {"fine", "mid", "coarse"})
      EXPECT_EQ(crashlink::run::list_checkpoints(ck.string(), d), instants) << interval << d;
    const std::string out = run_command(run + every + "--restart " + ck.string(), status);
    ASSERT_EQ(status, 0) << out;
    const std::string marker = "from the checkpoint at t = ";
    ASSERT_NE(out.find(marker), std::string::npos) << out;
    std::printf(
        "[measured] chain, variable steps, interval %s s: checkpoints kept at %lld, %lld, %lld "
        "ticks; restarted from t = %s s\n",
        interval.c_str(), static_cast<long long>(instants[0]), static_cast<long long>(instants[1]),
        static_cast<long long>(instants[2]),
        out.substr(out.find(marker) + marker.size(), 12).c_str());
    expect_same_results((dir / "ref" / "result.h5").string(), (ck / "result.h5").string(),
                        2);  // the first and the last field state
  }
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

// A damaged checkpoint (issue 20 item 4): one flipped byte in the newest checkpoint's copy of a
// domain's result file. The daemon finds it by the checkpoint's MANIFEST and does not offer that
// instant; the coordinator falls back to the previous complete one, says so, and the resumed run
// still ends with the bits of the run without checkpoints. Before, the restart used the damaged
// copy and exited 0 with other field values.
TEST(CheckpointRestartChain, ADamagedNewestCheckpointIsReportedAndThePreviousOneUsed) {
  const fs::path dir = fresh_dir("ckpt_damaged");
  const std::string scenario = chain3_scenario(dir);
  const std::string run = bin("crashlink") + " run " + scenario + " --mode multi --quiet ";
  int status = -1;
  const std::string out_ref = run_command(run + "--out " + (dir / "ref").string(), status);
  ASSERT_EQ(status, 0) << out_ref;
  const std::string every = "--checkpoint-interval 1.1e-4 ";
  const fs::path ck = dir / "ck";
  const std::string out_ck = run_command(run + every + "--out " + ck.string(), status);
  ASSERT_EQ(status, 0) << out_ck;
  const auto instants = crashlink::run::list_checkpoints(ck.string(), "coordinator");
  ASSERT_EQ(instants.size(), 3u) << out_ck;
  const fs::path copy =
      fs::path(crashlink::run::checkpoint_folder(ck.string(), instants.back(), "mid")) / "mid.h5";
  ASSERT_TRUE(fs::exists(copy));
  crashlink::proc_test::flip_middle_byte(copy);
  const std::string out = run_command(run + every + "--restart " + ck.string(), status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("checkpoint damaged, not offered for a restart"), std::string::npos) << out;
  EXPECT_NE(out.find("mid.h5: FNV-1a"), std::string::npos) << out;
  EXPECT_NE(out.find("is missing or damaged in mid: falling back"), std::string::npos) << out;
  const std::string marker = "from the checkpoint at t = ";
  ASSERT_NE(out.find(marker), std::string::npos) << out;
  const double from_s = std::stod(out.substr(out.find(marker) + marker.size()));
  std::printf("[measured] newest checkpoint %lld ticks damaged; restarted from t = %.6e s\n",
              static_cast<long long>(instants.back()), from_s);
  expect_same_results((dir / "ref" / "result.h5").string(), (ck / "result.h5").string(), 2);
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

// Two bars that do not touch, each cut in two: two leaders, whose instants never meet. Variable
// steps cannot checkpoint them together: refused before the run, naming both.
TEST(CheckpointRestartRefusals, VariableStepsWithTwoLeadersAreRefusedNamingThem) {
  const fs::path dir = fresh_dir("ckpt_two_leaders");
  std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "two_bars", 1e-4,
      {{"fine1", 0.0, 0.1, 20}, {"coarse1", 0.1, 0.1, 5}, {"fine2", 0.3, 0.1, 20}});
  // fine2 on its own (no node near another part's) and coarse2 merged with it
  const std::string merged = "  fine2:\n    material: steel\n    merge_nodes: true\n";
  ASSERT_NE(yaml.find(merged), std::string::npos) << yaml;
  yaml.replace(yaml.find(merged), merged.size(), "  fine2:\n    material: steel\n");
  const std::string parts_end = "node_sets:\n";
  yaml.insert(yaml.find(parts_end),
              "  coarse2:\n    material: steel\n    merge_nodes: true\n    mesh: {generator: bar, "
              "origin: [0.4, 0.0, 0.0], axis: x, length: 0.2, cross_section: [0.05, 0.05], "
              "divisions: 5}\n");
  yaml += "  coarse2: {parts: [coarse2]}\n";
  const std::string scenario = crashlink::proc_test::write_file(dir / "two.yaml", yaml);
  int status = -1;
  const std::string out = run_command(bin("crashlink") + " run " + scenario +
                                          " --mode multi --quiet --variable-steps "
                                          "--checkpoint-interval 2e-5 --out " +
                                          (dir / "out").string(),
                                      status);
  EXPECT_NE(status, 0) << out;
  EXPECT_NE(out.find("coordinator exited with code 2"), std::string::npos) << out;
  EXPECT_NE(out.find("need one leader"), std::string::npos) << out;
  EXPECT_NE(out.find("(coarse1, coarse2)"), std::string::npos) << out;
  const std::string plain =
      run_command(bin("crashlink") + " run " + scenario +
                      " --mode multi --quiet --variable-steps --out " + (dir / "plain").string(),
                  status);
  EXPECT_EQ(status, 0) << "without checkpoints the two groups run:\n" << plain;
}

TEST(CheckpointRestartRefusals, RestartWithoutCheckpointsIsRefusedNamingWhatEachHas) {
  const fs::path dir = fresh_dir("ckpt_none");
  int status = -1;
  const std::string out = run_command(
      bin("crashlink") + " run " + kScenario + " --mode multi --quiet --restart " + dir.string(),
      status);
  EXPECT_NE(status, 0) << out;
  EXPECT_NE(out.find("no checkpoint instant"), std::string::npos) << out;
  EXPECT_NE(out.find("wiper: []"), std::string::npos) << out;
  EXPECT_NE(out.find("run from the start without --restart"), std::string::npos) << out;
}

}  // namespace

// `lts` (docs/multirate.md "lts"): the fine side sends Fbar(T) p - 1 substeps after T, so its
// checkpoint at T is written before the owner used Fbar(T) and the owner's after; restored, the
// fine side must not send it again (the owner would refuse a force for an instant it has passed).
// Run with checkpoints and restarted from the newest, the run ends as the run without them.
static void lts_restart_case(const std::string& name, const std::string& yaml,
                             const std::string& extra, bool energy = true,
                             const std::string& interval = "1.1e-3", std::size_t checkpoints = 3,
                             const std::string& restart_env = "") {
  const fs::path dir = fresh_dir(name);
  const std::string scenario = crashlink::proc_test::write_file(dir / "scene.yaml", yaml);
  const std::string run =
      bin("crashlink") + " run " + scenario + " --mode multi --coupling lts --quiet " + extra;
  int status = -1;
  const std::string out_ref = run_command(run + "--out " + (dir / "ref").string(), status);
  ASSERT_EQ(status, 0) << out_ref;
  const std::string every = "--checkpoint-interval " + interval + " ";
  const fs::path ck = dir / "ck";
  const std::string out_ck = run_command(run + every + "--out " + ck.string(), status);
  ASSERT_EQ(status, 0) << out_ck;
  const auto instants = crashlink::run::list_checkpoints(ck.string(), "coordinator");
  ASSERT_EQ(instants.size(), checkpoints) << out_ck;
  const std::string out =
      run_command(restart_env + run + every + "--restart " + ck.string(), status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("from the checkpoint at t = "), std::string::npos) << out;
  expect_same_results((dir / "ref" / "result.h5").string(), (ck / "result.h5").string(), 2);
  // the scheme's energy too: each row's sum of the domains' shares (NaN before the third sample)
  const auto a = crashlink::io::ResultReader((dir / "ref" / "result.h5").string()).glstat();
  const auto b = crashlink::io::ResultReader((ck / "result.h5").string()).glstat();
  ASSERT_EQ(a.size(), b.size());
  std::size_t finite = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i].scheme_energy_J)) {
      EXPECT_TRUE(std::isnan(b[i].scheme_energy_J)) << "row " << i;
      continue;
    }
    ++finite;
    EXPECT_EQ(a[i].scheme_energy_J, b[i].scheme_energy_J) << "row " << i;
    EXPECT_EQ(a[i].scheme_energy_time_s, b[i].scheme_energy_time_s) << "row " << i;
  }
  if (energy) {
    EXPECT_GT(finite + 3, a.size());  // NaN only before the third sample
  } else {
    EXPECT_EQ(finite, 0u);  // variable steps: no E
  }
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

// The bar at H/h = 4.
TEST(CheckpointRestartLts, RestartedFromTheNewestCheckpointIsTheSameRun) {
  lts_restart_case("ckpt_lts", crashlink::proc_test::bar_yaml(6.0e-3), "");
}

// A chain of three (fine | mid | coarse bars of 5, 10 and 30 mm hexes: mid is the fine side of
// coarse and the owner of fine), step safety 0.8 as LayerProcesses' chain: each pair's Fbar(T)
// leaves p - 1 substeps after T, so the three checkpoints of an instant hold three different
// moments of the exchange. History rows every 10 us (the coarse step is 3 us): the daemons sample
// the energy only where a row reads it, and must take that up again after the restart.
TEST(CheckpointRestartLts, ChainOfThreeRestartedIsTheSameRun) {
  std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "chain3", 6.0e-3, {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}});
  const std::string key = "controls:\n";
  ASSERT_NE(yaml.find(key), std::string::npos);
  yaml.insert(yaml.find(key) + key.size(), "  history_interval: 1.0e-5\n");
  lts_restart_case("ckpt_lts_chain", yaml, "--step-safety 0.8 ");
}

// Variable steps (docs/multirate.md "Variable steps under lts"): the owner steps announced one
// ahead, the fine side pausing at the start of the owner step where its owner pauses. The bar,
// and the chain of three whose middle domain waits for its owner's announcement; no E (every row
// NaN in both runs).
TEST(CheckpointRestartLts, VariableStepsRestartedAreTheSameRun) {
  lts_restart_case("ckpt_lts_var", crashlink::proc_test::bar_yaml(6.0e-3), "--variable-steps ",
                   false);
}

TEST(CheckpointRestartLts, VariableStepsChainOfThreeRestartedIsTheSameRun) {
  const std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "chain3", 6.0e-3, {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}});
  lts_restart_case("ckpt_lts_var_chain", yaml, "--variable-steps --step-safety 0.8 ", false);
}

// The chain fine | mid | coarse whose mid (10 mm) takes one substep per owner step of coarse
// (10.7 mm hexes): mid decides its next owner step, and whether its owner pauses at its end, in
// the cycle it takes the current one up. Checkpoints every 1 us against a coarse step of about
// 1.3 us: every coarse instant is a checkpoint instant, so mid's pause at one and its owner's
// flag for the next meet in one cycle (before, mid missed every such pause), and the restart from
// the newest (the coordinator keeps the last 3) is the same run.
TEST(CheckpointRestartLts, VariableStepsChainWithOneSubstepAtEveryInstant) {
  const std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "chain3even", 3.0e-5,
      {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 28}});
  lts_restart_case("ckpt_lts_var_even", yaml, "--variable-steps ", false, "1.0e-6", 3);
}

// The same, restarted with 'coarse' slow to open its partners' lanes (docs/processes.md "Lanes").
// Restarted one coarse step before the end, 'mid' ends after one substep without coarse's last
// vector, which coarse still sends. Before the rule that a receiver keeps its files until every
// sender has opened them, mid took its files with it, and coarse, opening at that first send,
// failed on files that "did not appear within 5000 ms" (CI, 2026-11-28, under load).
TEST(LaneEnds, APartnerThatHasEndedStillLetsItsSenderOpenItsLane) {
  const std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "chain3even", 3.0e-5,
      {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 28}});
  lts_restart_case("lane_ends", yaml, "--variable-steps ", false, "1.0e-6", 3,
                   "CRASHLINK_INJECT_LANE_DELAY=coarse:3000 ");
}
