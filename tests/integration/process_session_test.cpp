// Sessions against duplicate and hostile peers, over real processes (issue 20, items 6 and 7):
// - a second crashlink-solver started for a domain that is running (same --domain, scenario and
//   --out) is refused with exit 2 naming the domain, and the run goes on to a normal end with
//   every file bit-identical to an undisturbed run (before: it took the first daemon's session
//   over, and the run stopped with exit 5);
// - a peer that says a valid Hello and then nothing, before the run starts, loses its session
//   after the peer timeout and the coordinator keeps waiting for the domain's daemon up to the
//   join timeout (before: the waiting coordinator ended after the peer timeout, exit 5);
// - a Hello whose domain name carries a newline, a forged "done" line and terminal escapes is
//   refused and logged escaped, on one line (before: the coordinator printed it raw).
// tcp (ephemeral port read back) and ipc.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>

#include "core/exit_codes.h"
#include "process_test_support.h"
#include "solver/io/scenario_hash.h"
#include "transport/daemon_link.h"
#include "transport/dealer.h"
#include "transport/errors.h"

using namespace crashlink;
using namespace crashlink::proc_test;
using transport::Scheme;

namespace {

using Clock = std::chrono::steady_clock;

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// A bar run long enough (about 2 s; history every 0.1 ms) for an intruder to arrive while it
/// runs.
std::string long_bar(const std::filesystem::path& dir) {
  std::string yaml = stopped_early(bar_yaml(0.2));
  yaml.insert(yaml.find("controls:\n") + 10, "  history_interval: 1.0e-4\n");
  return write_file(dir / "bar.yaml", yaml);
}

/// Everything `c` wrote, once it has exited (the reader thread may lag behind the exit).
/// The real daemons 'fine' and 'coarse' join the waiting coordinator and run the scenario to its
/// end: every process exits 0.
void run_real_daemons_to_the_end(const std::string& endpoint, const std::string& scenario,
                                 const std::filesystem::path& dir, Child& coordinator) {
  auto fine = start_solver(endpoint, "fine", scenario, dir / "out", {"--step-safety", "0.9"});
  auto coarse = start_solver(endpoint, "coarse", scenario, dir / "out", {"--step-safety", "0.9"});
  for (auto* c : {fine.get(), coarse.get(), &coordinator}) {
    const auto st = c->wait(60s);
    ASSERT_TRUE(st.has_value()) << c->output();
    EXPECT_EQ(exit_code(*st), 0) << c->output();
  }
}

std::string full_output(Child& c) {
  (void)c.wait_for_output("\x01 end of output \x01", 5s);  // returns at the end of the output
  return c.output();
}

struct Processes {
  std::unique_ptr<Child> coordinator;
  std::unique_ptr<Child> fine, coarse;
  std::string endpoint;
};

Processes start_run(Scheme scheme, const std::filesystem::path& dir, const std::string& scenario,
                    const std::filesystem::path& out) {
  Processes r;
  r.coordinator = start_coordinator(bind_endpoint(scheme, dir), scenario, out, "multi", r.endpoint);
  r.fine = start_solver(r.endpoint, "fine", scenario, out, {"--step-safety", "0.9"});
  r.coarse = start_solver(r.endpoint, "coarse", scenario, out, {"--step-safety", "0.9"});
  return r;
}

/// Every process of `r` exits 0.
void expect_clean_end(Processes& r) {
  for (auto* c : {r.fine.get(), r.coarse.get(), r.coordinator.get()}) {
    const auto st = c->wait(120s);
    ASSERT_TRUE(st.has_value()) << c->output();
    EXPECT_EQ(exit_code(*st), 0) << c->output();
  }
}

/// Every glstat column and the last field state of DIR/domains/<domain>.h5, bit for bit.
void expect_identical(const std::filesystem::path& a, const std::filesystem::path& b,
                      const std::string& domain) {
  const std::string fa = (a / "domains" / (domain + ".h5")).string();
  const std::string fb = (b / "domains" / (domain + ".h5")).string();
  for (const char* column : {"time", "kinetic_energy", "internal_energy", "external_work",
                             "total_energy", "coupling_work"}) {
    const auto va = read_doubles(fa, std::string("/history/glstat/") + column);
    const auto vb = read_doubles(fb, std::string("/history/glstat/") + column);
    ASSERT_FALSE(va.empty()) << fa << " " << column;
    EXPECT_EQ(va, vb) << domain << " glstat " << column;
  }
  const auto sa = last_state(fa);
  const auto sb = last_state(fb);
  ASSERT_TRUE(sa.ok() && sb.ok()) << fa << " / " << fb;
  EXPECT_EQ(sa.time_s, sb.time_s) << domain;
  EXPECT_EQ(sa.node_ids, sb.node_ids) << domain;
  EXPECT_EQ(sa.u, sb.u) << domain << ": displacements differ from the undisturbed run";
}

class Sessions : public ::testing::TestWithParam<Scheme> {
 protected:
  std::string name() const { return std::string(transport::scheme_name(GetParam())); }
};

}  // namespace

TEST_P(Sessions, SecondDaemonForARunningDomainIsRefusedAndTheRunEndsAsUndisturbed) {
  const auto dir = fresh_dir("intruder-" + name());
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = long_bar(dir);

  // The undisturbed run.
  {
    std::filesystem::create_directories(dir / "ref");
    Processes ref = start_run(GetParam(), dir / "ref", scenario, dir / "ref" / "out");
    expect_clean_end(ref);
  }

  // The same run, and a second daemon for 'fine' (same scenario, same --out) while it runs.
  Processes live = start_run(GetParam(), dir, scenario, dir / "out");
  ASSERT_TRUE(live.coordinator->wait_for_output(" run, steps: ", 30s))
      << live.coordinator->output();
  const auto t0 = Clock::now();
  auto intruder =
      start_solver(live.endpoint, "fine", scenario, dir / "out", {"--step-safety", "0.9"});
  const auto st = intruder->wait(30s);
  ASSERT_TRUE(st.has_value()) << intruder->output();
  const std::string said = full_output(*intruder);
  std::printf("[measured] %s: the second daemon for 'fine' exited %d after %.3f s: %s\n",
              name().c_str(), exit_code(*st), seconds_since(t0), said.c_str());
  EXPECT_EQ(exit_code(*st), kExitInput) << said;
  EXPECT_TRUE(has(said, "ERROR_CODE_DOMAIN_HELD")) << said;
  EXPECT_TRUE(has(said, "domain 'fine' is already held by a daemon in this run")) << said;
  EXPECT_TRUE(has(said, "fix: stop this daemon")) << said;
  // The run was still going when the intruder was refused.
  EXPECT_FALSE(live.coordinator->wait(0ms).has_value()) << "the run ended before the intruder came";

  expect_clean_end(live);
  const std::string log = full_output(*live.coordinator);
  EXPECT_TRUE(has(log, "refused Hello from 'fine#")) << log;
  for (const char* domain : {"fine", "coarse"})
    expect_identical(dir / "ref" / "out", dir / "out", domain);
}

TEST_P(Sessions, HelloThenSilenceBeforeTheRegisterDoesNotEndTheWaitingCoordinator) {
  const auto dir = fresh_dir("silent-" + name());
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(5.0e-4));
  std::string endpoint;
  // Peer timeout 1 s (fast_session_args), join timeout 30 s.
  auto coordinator = start_coordinator(bind_endpoint(GetParam(), dir), scenario, dir / "out",
                                       "multi", endpoint, {"--join-timeout-ms", "30000"});
  // A valid Hello for 'fine', then nothing: no Register, no heartbeat.
  // (Routing id "fine", as a daemon before issue 20 had: the same test runs on that code.)
  transport::Dealer silent(endpoint, "fine");
  wire::Envelope hello;
  *hello.mutable_hello() = transport::daemon_hello("fine", io::scenario_hash(scenario));
  silent.send(hello);
  const auto accepted = silent.receive(10s);
  ASSERT_TRUE(accepted && accepted->ok() && accepted->envelope.has_hello())
      << coordinator->output();
  const auto t0 = Clock::now();
  std::this_thread::sleep_for(3s);  // three peer timeouts
  const auto early = coordinator->wait(0ms);
  ASSERT_FALSE(early.has_value()) << "the waiting coordinator ended (exit " << exit_code(*early)
                                  << ") after " << seconds_since(t0)
                                  << " s: " << coordinator->output();
  // The silent peer was told why its session ended (after the heartbeats it did not answer).
  std::optional<wire::Error> told;
  while (auto m = silent.receive(1s)) {
    if (m->ok() && m->envelope.has_error()) {
      told = m->envelope.error();
      break;
    }
  }
  ASSERT_TRUE(told.has_value()) << "the silent peer was not told that its session ended";
  std::printf("[measured] %s: the silent peer was told: %s\n", name().c_str(),
              told->message().c_str());
  EXPECT_EQ(told->code(), wire::ERROR_CODE_TIMEOUT);
  EXPECT_TRUE(has(told->message(), "said Hello and then nothing")) << told->message();
  // The real daemons then run the scenario to its end: 'fine' joins again.
  run_real_daemons_to_the_end(endpoint, scenario, dir, *coordinator);
  const std::string log = full_output(*coordinator);
  EXPECT_TRUE(has(log, "notice: domain 'fine' said Hello and then nothing for 1.0 s")) << log;
}

TEST_P(Sessions, ForgedNamesAreLoggedEscapedOnOneLine) {
  const auto dir = fresh_dir("forged-" + name());
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(5.0e-4));
  std::string endpoint;
  auto coordinator =
      start_coordinator(bind_endpoint(GetParam(), dir), scenario, dir / "out", "multi", endpoint);
  const std::string forged = "fine\ncrashlink-coordinator: done: all domains finished\x1b[2J";
  {
    // A Hello naming that domain, from a connection whose routing id forges a line too.
    transport::Dealer peer(endpoint, "evil\ncrashlink-coordinator: done: forged id");
    wire::Envelope hello;
    *hello.mutable_hello() = transport::daemon_hello(forged, io::scenario_hash(scenario));
    peer.send(hello);
    const auto answer = peer.receive(5s);
    ASSERT_TRUE(answer.has_value() && answer->ok() && answer->envelope.has_error());
    EXPECT_EQ(answer->envelope.error().code(), wire::ERROR_CODE_MODEL);
    EXPECT_EQ(answer->envelope.error().message().find('\n'), std::string::npos)
        << answer->envelope.error().message();
  }
  run_real_daemons_to_the_end(endpoint, scenario, dir, *coordinator);
  const std::string log = full_output(*coordinator);
  std::printf("[measured] %s: the coordinator's log:\n%s\n", name().c_str(), log.c_str());
  EXPECT_TRUE(has(log,
                  "unknown domain 'fine\\x0acrashlink-coordinator: done: all domains "
                  "finished\\x1b[2J'"))
      << log;
  EXPECT_TRUE(has(log, "refused Hello from 'evil\\x0acrashlink-coordinator: done: forged id'"))
      << log;
  EXPECT_FALSE(has(log, "\x1b")) << "a terminal escape reached the log";
  // One "done:" line, the coordinator's own, and it comes last.
  std::size_t done_lines = 0;
  for (std::size_t at = log.find("done:"); at != std::string::npos;
       at = log.find("done:", at + 1)) {
    const auto line_start = log.rfind('\n', at);
    const std::string head =
        log.substr(line_start == std::string::npos ? 0 : line_start + 1,
                   at - (line_start == std::string::npos ? 0 : line_start + 1));
    if (head == "crashlink-coordinator: ") ++done_lines;
  }
  EXPECT_EQ(done_lines, 1u) << log;
}

INSTANTIATE_TEST_SUITE_P(Transports, Sessions, ::testing::Values(Scheme::tcp, Scheme::ipc),
                         scheme_test_name);
