// Failure handling of a `layer` or `paper` run over real processes (docs/design.md §3, issue 4
// "Failure handling"): a daemon killed (SIGKILL) or frozen (SIGSTOP) mid-run, or the coordinator
// killed. Everyone else must exit non-zero within 5 s with a message naming the culprit, and the
// output written so far must open (each daemon's DIR/domains/<domain>.h5 and the gathered
// result.h5). Heartbeat 100 ms, peer timeout 1 s. Runs over tcp (ephemeral port read back) and ipc;
// inproc has no process to kill.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "core/exit_codes.h"
#include "process_test_support.h"
#include "solver/gather/gather_results.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"

using namespace crashlink;
using namespace crashlink::proc_test;
using transport::Scheme;

namespace {

/// (transport, `paper` instead of `layer`)
using FailureCase = std::tuple<Scheme, bool>;

std::string failure_case_name(const ::testing::TestParamInfo<FailureCase>& info) {
  return std::string(transport::scheme_name(std::get<0>(info.param))) +
         (std::get<1>(info.param) ? "_paper" : "_layer");
}

class ProcessFailure : public ::testing::TestWithParam<FailureCase> {
 protected:
  Scheme scheme() const { return std::get<0>(GetParam()); }
  bool paper() const { return std::get<1>(GetParam()); }

  /// Coordinator + daemons 'fine' and 'coarse' on a bar that would run for minutes, started and
  /// past their Setup. `paper` runs split (one common step: stable for minutes; at the bar's
  /// ratio of 4 its guard would stop it within microseconds of simulated time).
  void start(const std::string& label) {
    dir_ = fresh_dir(label + "-" + std::string(transport::scheme_name(scheme())) +
                     (paper() ? "-paper" : ""));
    scenario_ = write_file(dir_ / "bar.yaml", stopped_early(bar_yaml(10.0)));
    out_ = dir_ / "out";
    std::vector<std::string> coupling;
    if (paper()) coupling = {"--coupling", "paper"};
    coordinator_ = start_coordinator(bind_endpoint(scheme(), dir_), scenario_, out_,
                                     paper() ? "split" : "multi", endpoint_, coupling);
    auto solver_args = coupling;
    solver_args.insert(solver_args.end(), {"--step-safety", "0.9"});
    fine_ = start_solver(endpoint_, "fine", scenario_, out_, solver_args);
    coarse_ = start_solver(endpoint_, "coarse", scenario_, out_, solver_args);
    ASSERT_TRUE(coordinator_->wait_for_output("steps:", 20s)) << coordinator_->output();
    // Mid-run: both daemons have been stepping (and flushing history) for a while.
    std::this_thread::sleep_for(500ms);
  }

  /// Waits for `c` to exit within `limit` of `since`; returns the exit code and the time taken.
  static std::pair<int, double> ends(Child& c, Clock::time_point since,
                                     std::chrono::seconds limit) {
    const auto st = c.wait(limit + 1s);
    if (!st) return {-999, 1e9};
    return {exit_code(*st), std::chrono::duration<double>(c.exited_at() - since).count()};
  }

  /// The daemon's own file and the gathered result.h5 open and hold history.
  void expect_readable_output(const std::string& survivor) {
    io::ResultReader own((out_ / "domains" / (survivor + ".h5")).string());
    EXPECT_FALSE(own.glstat().empty()) << survivor;
    const auto model = io::read_scenario(scenario_);
    const auto dec =
        partition::decompose(model, paper() ? partition::Scheme::Paper : partition::Scheme::Layer);
    const auto report = gather::gather_results(model, dec, out_.string());
    io::ResultReader gathered((out_ / "result.h5").string());
    EXPECT_FALSE(gathered.glstat().empty());
    std::printf(
        "[measured]   gathered result.h5: %lld history rows up to t = %.4e s from %zu "
        "domain files\n",
        static_cast<long long>(report.history_samples), report.end_time_s,
        report.domains_read.size());
  }

  void TearDown() override {
    for (auto* c : {&coordinator_, &fine_, &coarse_}) {
      if (*c) (*c)->signal(SIGCONT);  // a frozen one can then be killed and reaped
      c->reset();
    }
    if (!dir_.empty()) RemoveIfPassed{dir_};
  }

  std::filesystem::path dir_, out_;
  std::string scenario_, endpoint_;
  std::unique_ptr<Child> coordinator_, fine_, coarse_;
};

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_P(ProcessFailure, KilledDaemonStopsEveryoneWithinFiveSeconds) {
  ASSERT_NO_FATAL_FAILURE(start("kill"));
  const auto t0 = Clock::now();
  fine_->signal(SIGKILL);
  const auto [cc, ct] = ends(*coordinator_, t0, 5s);
  const auto [dc, dt] = ends(*coarse_, t0, 5s);
  std::printf(
      "[measured] %s: daemon 'fine' SIGKILLed: coordinator exit %d after %.3f s, daemon "
      "'coarse' exit %d after %.3f s (peer timeout 1 s)\n",
      transport::scheme_name(scheme()).data(), cc, ct, dc, dt);
  EXPECT_NE(cc, 0);
  EXPECT_NE(dc, 0);
  EXPECT_LE(ct, 5.0);
  EXPECT_LE(dt, 5.0);
  EXPECT_TRUE(has(coordinator_->output(), "domain 'fine'")) << coordinator_->output();
  EXPECT_TRUE(has(coarse_->output(), "'fine'")) << coarse_->output();
  expect_readable_output("coarse");
}

TEST_P(ProcessFailure, FrozenDaemonIsDetectedAsSilent) {
  ASSERT_NO_FATAL_FAILURE(start("stop"));
  const auto t0 = Clock::now();
  coarse_->signal(SIGSTOP);
  const auto [cc, ct] = ends(*coordinator_, t0, 5s);
  const auto [dc, dt] = ends(*fine_, t0, 5s);
  std::printf(
      "[measured] %s: daemon 'coarse' SIGSTOPped: coordinator exit %d after %.3f s, "
      "daemon 'fine' exit %d after %.3f s (peer timeout 1 s)\n",
      transport::scheme_name(scheme()).data(), cc, ct, dc, dt);
  EXPECT_EQ(cc, kExitPeer);
  EXPECT_EQ(dc, kExitPeer);
  EXPECT_GE(ct, 0.9);  // not before the peer timeout
  EXPECT_LE(ct, 5.0);
  EXPECT_LE(dt, 5.0);
  const std::string log = coordinator_->output();
  EXPECT_TRUE(has(log, "domain 'coarse'") && has(log, "silent")) << log;
  EXPECT_TRUE(has(fine_->output(), "'coarse'")) << fine_->output();
  // Woken up, the frozen daemon finds its coordinator gone and stops by itself.
  coarse_->signal(SIGCONT);
  const auto st = coarse_->wait(5s);
  ASSERT_TRUE(st.has_value()) << coarse_->output();
  EXPECT_NE(exit_code(*st), 0) << coarse_->output();
  expect_readable_output("fine");
}

TEST_P(ProcessFailure, KilledCoordinatorStopsTheDaemons) {
  ASSERT_NO_FATAL_FAILURE(start("coord"));
  const auto t0 = Clock::now();
  coordinator_->signal(SIGKILL);
  const auto [fc, ft] = ends(*fine_, t0, 5s);
  const auto [dc, dt] = ends(*coarse_, t0, 5s);
  std::printf(
      "[measured] %s: coordinator SIGKILLed: daemon 'fine' exit %d after %.3f s, daemon "
      "'coarse' exit %d after %.3f s (peer timeout 1 s)\n",
      transport::scheme_name(scheme()).data(), fc, ft, dc, dt);
  EXPECT_EQ(fc, kExitPeer);
  EXPECT_EQ(dc, kExitPeer);
  EXPECT_LE(ft, 5.0);
  EXPECT_LE(dt, 5.0);
  EXPECT_TRUE(has(fine_->output(), "the coordinator")) << fine_->output();
  EXPECT_TRUE(has(coarse_->output(), "the coordinator")) << coarse_->output();
  for (const std::string d : {"fine", "coarse"}) {
    io::ResultReader r((out_ / "domains" / (d + ".h5")).string());
    EXPECT_FALSE(r.glstat().empty()) << d;
  }
}

INSTANTIATE_TEST_SUITE_P(Transports, ProcessFailure,
                         ::testing::Combine(::testing::Values(Scheme::tcp, Scheme::ipc),
                                            ::testing::Bool()),
                         failure_case_name);
