// A stop on request (issue 20 item 2): SIGTERM or SIGINT to `crashlink run` (what `kill PID`,
// Ctrl-C or a batch scheduler's cancel sends) stops every process of the run at once, each
// flushing its file, and the launcher exits with kExitStopped and says "stopped on request",
// in mono and in multi over ipc, tcp and inproc. Before, the launcher held the request for the peer
// timeout + heartbeat + 2 s (7.5 s by default) and a run that ended meanwhile exited 0.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "core/exit_codes.h"
#include "solver/io/result_reader.h"
#include "tests/integration/process_test_support.h"
#include "transport/endpoint.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using crashlink::proc_test::bin;
using crashlink::proc_test::Child;
using crashlink::proc_test::exit_code;
using crashlink::proc_test::fresh_dir;

struct StopCase {
  std::string name;
  std::string mode;       // mono, multi
  std::string transport;  // ipc, tcp, inproc (multi)
  int signal = SIGTERM;
};

void PrintTo(const StopCase& c, std::ostream* os) {
  *os << c.name;
}

class StopRequest : public ::testing::TestWithParam<StopCase> {};

// A three-part bar with an end time of 1 s of simulated time: minutes of work, so the run is
// surely in its cycles when the signal comes.
TEST_P(StopRequest, EveryProcessStopsAtOnceWithItsFileReadable) {
  const auto& c = GetParam();
  const fs::path dir = fresh_dir("stop_" + c.name);
  const std::string scenario = crashlink::proc_test::write_file(
      dir / "bar.yaml", crashlink::proc_test::bar_parts_yaml(
                            "stopbar", 1.0, {{"left", 0.0, 0.2, 20}, {"right", 0.2, 0.4, 10}}));
  std::vector<std::string> argv{bin("crashlink"),      "run", scenario, "--mode", c.mode, "--out",
                                (dir / "out").string()};
  if (c.mode != "mono") {
    argv.emplace_back("--transport");
    argv.push_back(c.transport);
  }
  Child run(argv);
  // the domains' (or mono's) file exists and the progress line moves: the run is in its cycles
  const fs::path h5 =
      c.mode == "mono" ? dir / "out" / "result.h5" : dir / "out" / "domains" / "left.h5";
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (!fs::exists(h5) && std::chrono::steady_clock::now() < deadline)
    ASSERT_FALSE(run.wait(20ms).has_value()) << run.output();
  ASSERT_FALSE(run.wait(500ms).has_value()) << run.output();

  const auto sent = std::chrono::steady_clock::now();
  run.signal(c.signal);
  const auto status = run.wait(20s);
  ASSERT_TRUE(status.has_value()) << "still running 20 s after the signal:\n" << run.output();
  const double took_s = std::chrono::duration<double>(run.exited_at() - sent).count();
  std::printf("[measured] %s: every process stopped %.3f s after signal %d\n", c.name.c_str(),
              took_s, c.signal);
  EXPECT_EQ(exit_code(*status), crashlink::kExitStopped) << run.output();
  EXPECT_NE(run.output().find("stopped on request"), std::string::npos) << run.output();
  // 1 s asked, 38-79 ms measured on a quiet machine. The bound includes flushing three files
  // and gathering a fourth, and a flush took over 1 s with both cores busy: 2.36 s was seen
  // once with two CPU hogs beside the suite (2026-11-27). The launcher that held the request
  // (7.5 s before issue 20) still fails it.
  EXPECT_LT(took_s, 4.0) << run.output();

  // what was written is readable, up to the stop and not beyond the end
  const fs::path result = dir / "out" / "result.h5";
  ASSERT_TRUE(fs::exists(result)) << run.output();
  const crashlink::io::ResultReader r(result.string());
  const auto g = r.glstat();
  ASSERT_FALSE(g.empty()) << run.output();
  EXPECT_GT(g.back().time_s, 0.0);
  EXPECT_LT(g.back().time_s, 1.0);
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Runs, StopRequest,
                         ::testing::Values(StopCase{"mono_term", "mono", "", SIGTERM},
                                           StopCase{"mono_int", "mono", "", SIGINT},
                                           StopCase{"multi_ipc_term", "multi", "ipc", SIGTERM},
                                           StopCase{"multi_ipc_int", "multi", "ipc", SIGINT},
                                           StopCase{"multi_tcp_term", "multi", "tcp", SIGTERM},
                                           StopCase{"multi_inproc_term", "multi", "inproc",
                                                    SIGTERM}),
                         [](const ::testing::TestParamInfo<StopCase>& i) { return i.param.name; });

/// SIGTERM to a waiting daemon: it ends with exit 7 within 2 s (1 s asked; the margin is for a
/// loaded machine). Prints the time as `what`.
void expect_stops_on_sigterm(Child& daemon, const char* what) {
  ASSERT_FALSE(daemon.wait(1500ms).has_value()) << daemon.output();
  const auto sent = std::chrono::steady_clock::now();
  daemon.signal(SIGTERM);
  const auto st = daemon.wait(20s);
  ASSERT_TRUE(st.has_value()) << daemon.output();
  const double took = std::chrono::duration<double>(daemon.exited_at() - sent).count();
  std::printf("[measured] a daemon waiting for %s stopped %.3f s after SIGTERM\n", what, took);
  EXPECT_EQ(exit_code(*st), crashlink::kExitStopped) << daemon.output();
  EXPECT_LT(took, 2.0) << daemon.output();
}

/// The pid of the launcher's child that runs `domain` (from /proc: children, command lines).
pid_t daemon_pid(pid_t launcher, const std::string& domain) {
  std::ifstream kids("/proc/" + std::to_string(launcher) + "/task/" + std::to_string(launcher) +
                     "/children");
  pid_t pid = 0;
  while (kids >> pid) {
    std::ifstream cmd("/proc/" + std::to_string(pid) + "/cmdline", std::ios::binary);
    const std::string line((std::istreambuf_iterator<char>(cmd)), std::istreambuf_iterator<char>());
    if (line.find(std::string("--domain") + '\0' + domain + '\0') != std::string::npos) return pid;
  }
  return 0;
}

/// A process that has exited (gone, or a zombie its parent has not reaped yet).
bool ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string pid_field, comm, state;
  return !(stat >> pid_field >> comm >> state) || state == "Z";
}

// SIGTERM to one daemon (a user's `kill` of one piece) whose partner is frozen (SIGSTOP): it
// stops at once although it waits on its lane for the frozen partner, and once the partner runs
// again every piece has stopped with exit 7 and so has the launcher. Before: the daemon waited
// out the peer timeout on its lane (4.7 s, exit 5) and the launcher said 5.
TEST(StopRequest, ASignalToOnePieceStopsItAtOnceAndTheRunWithExit7) {
  const fs::path dir = fresh_dir("stop_one");
  const std::string scenario = crashlink::proc_test::write_file(
      dir / "bar.yaml", crashlink::proc_test::bar_parts_yaml(
                            "stopbar", 1.0, {{"left", 0.0, 0.2, 20}, {"right", 0.2, 0.4, 10}}));
  Child run(
      {bin("crashlink"), "run", scenario, "--mode", "multi", "--out", (dir / "out").string()});
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (!fs::exists(dir / "out" / "domains" / "left.h5") &&
         std::chrono::steady_clock::now() < deadline)
    ASSERT_FALSE(run.wait(20ms).has_value()) << run.output();
  ASSERT_FALSE(run.wait(500ms).has_value()) << run.output();
  const pid_t left = daemon_pid(run.pid(), "left"), right = daemon_pid(run.pid(), "right");
  ASSERT_GT(left, 0);
  ASSERT_GT(right, 0);
  ::kill(left, SIGSTOP);
  const auto sent = std::chrono::steady_clock::now();
  ::kill(right, SIGTERM);
  while (!ended(right) && std::chrono::steady_clock::now() < sent + 20s)
    std::this_thread::sleep_for(2ms);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ::kill(left, SIGCONT);
  std::printf("[measured] a daemon whose partner is frozen stopped %.3f s after SIGTERM\n", took);
  EXPECT_LT(took, 2.0) << run.output();
  const auto st = run.wait(30s);
  ASSERT_TRUE(st.has_value()) << run.output();
  EXPECT_EQ(exit_code(*st), crashlink::kExitStopped) << run.output();
  EXPECT_NE(run.output().find("domain 'right' at t = "), std::string::npos) << run.output();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

// A daemon still waiting: for the coordinator's answer to its Hello (no coordinator), and for its
// Setup (the other domain never joins). Before, the first waited out its handshake timeout (30 s
// and exit 5), the second its peer timeout per wait.
TEST(StopRequest, AWaitingDaemonStopsAtOnceAndTheCoordinatorWithIt) {
  const fs::path dir = fresh_dir("stop_waiting");
  const std::string scenario =
      crashlink::proc_test::write_file(dir / "bar.yaml", crashlink::proc_test::bar_yaml(1e-3));
  {
    // nobody listens on the discard port of the loopback: the Hello goes unanswered
    Child alone(
        crashlink::proc_test::solver_args("tcp://127.0.0.1:9", "fine", scenario, dir / "alone"));
    expect_stops_on_sigterm(alone, "the Hello's answer");
  }
  std::string endpoint;
  auto coordinator = crashlink::proc_test::start_coordinator(
      crashlink::proc_test::bind_endpoint(crashlink::transport::Scheme::tcp, dir), scenario,
      dir / "out", "multi", endpoint);
  Child fine(crashlink::proc_test::solver_args(endpoint, "fine", scenario, dir / "out"));
  // registered, it waits for the Setup, which needs the other domain too
  expect_stops_on_sigterm(fine, "its Setup");
  const auto cs = coordinator->wait(20s);
  ASSERT_TRUE(cs.has_value()) << coordinator->output();
  EXPECT_EQ(exit_code(*cs), crashlink::kExitStopped) << coordinator->output();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
