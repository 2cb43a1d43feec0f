// A third coupling scheme, "hold" (tests/support/hold_scheme.h), built in the test suite to show
// what adding one takes: its file and one registration line per side. It runs through the same
// daemon and coordinator code as `layer` and `paper`, over threads on one ZeroMQ context (inproc,
// `crashlink run --transport inproc`'s path) and over processes: crashlink-solver-hold and
// crashlink-coordinator-hold (tests/programs/) are the product's programs with "hold" registered
// first. At equal steps "hold" is [8] exactly and must reproduce the in-process `paper` runner
// without [11] bit for bit; at a step ratio of 2 it differs from `paper` (which interpolates by
// [10]) and must still run to the end.
#include "tests/support/hold_scheme.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "inproc_run.h"
#include "paper_reference.h"
#include "process_test_support.h"
#include "solver/daemon/daemon.h"
#include "solver/io/scenario_reader.h"

using namespace crashlink;
using namespace crashlink::proc_test;

namespace {

constexpr double kFineStep = 1.0e-6;  // s; the bar's fine part allows ~1.1e-6 s

/// The coordinator and one daemon per domain of the bar as threads over inproc, the coarse step
/// capped at `ratio` fine steps. Returns the coordinator's exit code; messages in `log`.
int run_hold(const std::string& scenario, const std::filesystem::path& out, int ratio,
             std::string& log) {
  test_schemes::register_hold();
  coordinator::CoordinatorOptions co;
  co.bind = transport::local_endpoint(transport::Scheme::inproc, "hold");
  co.scenario = scenario;
  co.out_dir = out.string();
  co.run.common_step = false;
  co.run.scheme = "hold";
  const auto r = run_inproc(co, {{"fine", kFineStep}, {"coarse", ratio * kFineStep}});
  log = r.coordinator.message;
  for (const auto& d : r.daemons) log += "\n" + d.message;
  for (const auto& d : r.daemons)
    if (d.exit_code != 0) return d.exit_code;
  return r.coordinator.exit_code;
}

/// The same as separate processes over `scheme`: the coordinator and the two daemons are
/// crashlink-coordinator-hold and crashlink-solver-hold. Returns the coordinator's exit code.
int run_hold_processes(const std::string& scenario, const std::filesystem::path& out, int ratio,
                       transport::Scheme scheme, std::string& log) {
  const std::string programs = std::string(CRASHLINK_BINARY_DIR) + "/tests/";
  std::string endpoint;
  auto c = start_coordinator(bind_endpoint(scheme, out), scenario, out, "multi", endpoint,
                             {"--coupling", "hold"}, programs + "crashlink-coordinator-hold");
  std::vector<std::unique_ptr<Child>> ds;
  for (const auto& [name, step] :
       std::map<std::string, double>{{"fine", kFineStep}, {"coarse", ratio * kFineStep}})
    ds.push_back(start_solver(
        endpoint, name, scenario, out,
        {"--coupling", "hold", "--max-step", fmt::format("{:.17g}", step), "--step-safety", "1"},
        programs + "crashlink-solver-hold"));
  int worst = 0;
  for (auto& d : ds) {
    const auto st = d->wait(60s);
    EXPECT_TRUE(st.has_value()) << d->output();
    if (!st || exit_code(*st) != 0) worst = st ? exit_code(*st) : -999;
  }
  const auto st = c->wait(20s);
  log = c->output();
  for (auto& d : ds) log += "\n" + d->output();
  if (worst != 0) return worst;
  return st ? exit_code(*st) : -999;
}

TEST(HoldScheme, AtEqualStepsIsThePaperLinkWithoutDriftBitForBit) {
  const auto dir = fresh_dir("hold-r1");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(5.0e-5));
  const auto out = dir / "out";
  std::string log;
  ASSERT_EQ(run_hold(scenario, out, 1, log), 0) << log;
  std::string stopped;
  const auto ref =
      reference(io::read_scenario(scenario), kFineStep, kFineStep, 50, stopped, /*drift=*/false);
  ASSERT_TRUE(stopped.empty()) << stopped;
  expect_runner_bits(out, *ref, "fine", "coarse");
}

TEST(HoldScheme, AtRatioTwoHoldsInsteadOfInterpolatingAndRunsToTheEnd) {
  const auto dir = fresh_dir("hold-r2");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(5.0e-5));
  const auto out = dir / "out";
  std::string log;
  ASSERT_EQ(run_hold(scenario, out, 2, log), 0) << log;
  std::string stopped;
  const auto ref = reference(io::read_scenario(scenario), kFineStep, 2 * kFineStep, 25, stopped,
                             /*drift=*/false);
  ASSERT_TRUE(stopped.empty()) << stopped;
  // The same instant as the interpolating runner's end, finite, and not its numbers: the fine
  // domain's odd instants saw the coarse side's value held, not interpolated.
  const auto s = last_state((out / "domains" / "fine.h5").string());
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s.time_s, ref->seconds(ref->coarse_time_ticks()), 1e-12);
  for (const double u : s.u) ASSERT_TRUE(std::isfinite(u));
  const double diff = max_difference(s, ref->fine());
  EXPECT_GT(diff, 0.0) << "hold gave the interpolating runner's numbers";
  double largest = 0.0;
  for (const double u : s.u) largest = std::max(largest, std::abs(u));
  // Holding is first-order in the coarse step where [10] is second-order: measured 6.4 % of the
  // largest displacement after 25 coarse steps; a quarter would mean a different motion.
  EXPECT_LT(diff, 0.25 * largest) << "hold strayed far from the interpolated coupling";
}

TEST(HoldScheme, OverProcessesAtEqualStepsIsThePaperLinkWithoutDriftBitForBit) {
  for (const auto scheme : {transport::Scheme::ipc, transport::Scheme::tcp}) {
    SCOPED_TRACE(transport::scheme_name(scheme));
    const auto dir =
        fresh_dir(std::string("hold-p-") + std::string(transport::scheme_name(scheme)));
    const RemoveIfPassed cleanup{dir};
    const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(5.0e-5));
    const auto out = dir / "out";
    std::string log;
    ASSERT_EQ(run_hold_processes(scenario, out, 1, scheme, log), 0) << log;
    std::string stopped;
    const auto ref =
        reference(io::read_scenario(scenario), kFineStep, kFineStep, 50, stopped, /*drift=*/false);
    ASSERT_TRUE(stopped.empty()) << stopped;
    expect_runner_bits(out, *ref, "fine", "coarse");
  }
}

TEST(HoldScheme, OverProcessesAtRatioTwoGivesTheThreadsRunsNumbers) {
  const auto dir = fresh_dir("hold-p2");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(5.0e-5));
  std::string log;
  ASSERT_EQ(run_hold(scenario, dir / "threads", 2, log), 0) << log;
  ASSERT_EQ(run_hold_processes(scenario, dir / "processes", 2, transport::Scheme::ipc, log), 0)
      << log;
  for (const std::string name : {"fine", "coarse"}) {
    const auto a = last_state((dir / "threads" / "domains" / (name + ".h5")).string());
    const auto b = last_state((dir / "processes" / "domains" / (name + ".h5")).string());
    ASSERT_TRUE(a.ok() && b.ok()) << name;
    EXPECT_EQ(a.time_s, b.time_s) << name;
    ASSERT_EQ(a.u.size(), b.u.size()) << name;
    for (std::size_t i = 0; i < a.u.size(); ++i)
      ASSERT_EQ(a.u[i], b.u[i]) << name << " u[" << i << "]";
  }
}

}  // namespace
