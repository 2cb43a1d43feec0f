// CURVE over real processes (docs/processes.md, "Security (CURVE)"): crashlink keygen,
// crashlink-coordinator and crashlink-solver with --curve on loopback tcp (ephemeral port read
// back). Encryption must not change the run: the domains' results are bit-identical to the same
// run without CURVE. A solver whose key is not authorised exits at once with the refusal (exit
// code 2) and the coordinator's log names its key and address; a coordinator that binds every
// interface without keys exits with the typed error. Every wait is bounded.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "process_test_support.h"

using namespace crashlink;
using namespace crashlink::proc_test;

namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `crashlink keygen --out DIR/name`; returns the public key (the last line of name.pub).
std::string keygen(const std::filesystem::path& dir, const std::string& name) {
  Child k({bin("crashlink"), "keygen", "--out", (dir / name).string()});
  const auto st = k.wait(20s);
  EXPECT_TRUE(st && exit_code(*st) == 0) << k.output();
  const std::string pub = read_text(dir / (name + ".pub"));
  const auto end = pub.find_last_not_of('\n');
  const auto begin = pub.rfind('\n', end);
  return pub.substr(begin + 1, end - begin);
}

struct Keys {
  std::filesystem::path dir;
  std::string stranger_pub;

  std::string file(const std::string& name) const { return (dir / name).string(); }
  std::vector<std::string> coordinator() const {
    return {"--curve", "--curve-secret-key", file("coordinator.key"), "--curve-authorized-keys",
            file("authorized")};
  }
  std::vector<std::string> daemon(const std::string& name) const {
    return {"--curve", "--curve-secret-key", file(name + ".key"), "--curve-server-key",
            file("coordinator.pub")};
  }
};

Keys make_keys(const std::filesystem::path& dir) {
  Keys k{dir / "keys", {}};
  std::filesystem::create_directories(k.dir);
  (void)keygen(k.dir, "coordinator");
  const std::string fine = keygen(k.dir, "fine");
  const std::string coarse = keygen(k.dir, "coarse");
  k.stranger_pub = keygen(k.dir, "stranger");
  write_file(k.dir / "authorized", "# the bar's daemons\n" + fine + "\n" + coarse + "\n");
  return k;
}

/// The bar (fine/coarse) over tcp on loopback (multi, step safety 0.9), every process with its
/// CURVE flags when `keys` is given; true when every process exited 0.
bool run_bar(const std::string& scenario, const std::filesystem::path& out, const Keys* keys) {
  std::string endpoint;
  auto c = start_coordinator("tcp://127.0.0.1:*", scenario, out, "multi", endpoint,
                             keys ? keys->coordinator() : std::vector<std::string>{});
  EXPECT_TRUE(endpoint.starts_with("tcp://127.0.0.1:")) << c->output();
  std::vector<std::unique_ptr<Child>> ds;
  for (const std::string d : {"fine", "coarse"}) {
    std::vector<std::string> extra = {"--step-safety", "0.9"};
    if (keys) {
      for (const auto& a : keys->daemon(d)) extra.push_back(a);
    }
    ds.push_back(start_solver(endpoint, d, scenario, out, extra));
  }
  bool ok = true;
  for (auto& d : ds) {
    const auto st = d->wait(60s);
    EXPECT_TRUE(st && exit_code(*st) == 0) << d->output();
    ok = ok && st && exit_code(*st) == 0;
  }
  const auto st = c->wait(20s);
  EXPECT_TRUE(st && exit_code(*st) == 0) << c->output();
  EXPECT_FALSE(has(c->output(), "refused")) << c->output();
  return ok && st && exit_code(*st) == 0;
}

TEST(CurveProcesses, ForcedCurveOnLoopbackGivesBitIdenticalResults) {
  const auto dir = fresh_dir("curve-bar");
  const RemoveIfPassed cleanup{dir};
  const Keys keys = make_keys(dir);
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(3.0e-3));
  const auto t0 = Clock::now();
  ASSERT_TRUE(run_bar(scenario, dir / "plain", nullptr));
  const auto t1 = Clock::now();
  ASSERT_TRUE(run_bar(scenario, dir / "curve", &keys));
  const auto t2 = Clock::now();
  std::size_t values = 0;
  for (const std::string d : {"fine", "coarse"}) {
    const auto plain = last_state((dir / "plain" / "domains" / (d + ".h5")).string());
    const auto curve = last_state((dir / "curve" / "domains" / (d + ".h5")).string());
    ASSERT_TRUE(plain.ok()) << d;
    ASSERT_TRUE(curve.ok()) << d;
    EXPECT_NEAR(plain.time_s, 3.0e-3, 1e-5) << d << ": the run did not reach the end time";
    EXPECT_EQ(curve.time_s, plain.time_s) << d;
    EXPECT_EQ(curve.node_ids, plain.node_ids) << d;
    ASSERT_EQ(curve.u.size(), plain.u.size()) << d;
    EXPECT_EQ(std::memcmp(curve.u.data(), plain.u.data(), plain.u.size() * sizeof(double)), 0)
        << d << ": the run with CURVE differs from the run without";
    values += plain.u.size();
  }
  std::printf(
      "[measured] bar fine/coarse (multi) over tcp loopback to t = 3 ms: %zu final displacement "
      "values bit-identical with and without CURVE; wall %.2f s plain, %.2f s CURVE\n",
      values, std::chrono::duration<double>(t1 - t0).count(),
      std::chrono::duration<double>(t2 - t1).count());
}

TEST(CurveProcesses, UnauthorisedSolverExitsAtOnceAndIsLogged) {
  const auto dir = fresh_dir("curve-refused");
  const RemoveIfPassed cleanup{dir};
  const Keys keys = make_keys(dir);
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(3.0e-3));
  std::string endpoint;
  auto c = start_coordinator("tcp://127.0.0.1:*", scenario, dir / "out", "multi", endpoint,
                             keys.coordinator());
  // A handshake timeout of 60 s: the refusal must come from the handshake, not the timeout.
  auto args = solver_args(endpoint, "fine", scenario, dir / "out");
  for (const std::string a :
       {"--heartbeat-ms", "100", "--timeout-ms", "1000", "--handshake-timeout-ms", "60000"}) {
    args.push_back(a);
  }
  for (const auto& a : keys.daemon("stranger")) args.push_back(a);
  const auto t0 = Clock::now();
  Child solver(args);
  const auto st = solver.wait(20s);
  ASSERT_TRUE(st.has_value()) << "the refused solver still runs after 20 s\n" << solver.output();
  const double seconds = std::chrono::duration<double>(solver.exited_at() - t0).count();
  std::printf("[measured] refused crashlink-solver exited after %.3f s with code %d\n", seconds,
              exit_code(*st));
  EXPECT_LT(seconds, 10.0);
  EXPECT_EQ(exit_code(*st), 2) << solver.output();
  EXPECT_TRUE(has(solver.output(), "refused this daemon's CURVE key")) << solver.output();
  EXPECT_TRUE(has(solver.output(), keys.stranger_pub)) << solver.output();
  EXPECT_TRUE(c->wait_for_output("client public key " + keys.stranger_pub, 5s)) << c->output();
  EXPECT_TRUE(has(c->output(), "notice: refused a CURVE connection from 127.0.0.1:"))
      << c->output();
}

TEST(CurveProcesses, CoordinatorOnEveryInterfaceWithoutKeysIsAnInputError) {
  const auto dir = fresh_dir("curve-nokeys");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(3.0e-3));
  Child c({bin("crashlink-coordinator"), "--bind", "tcp://0.0.0.0:*", "--scenario", scenario,
           "--out", (dir / "out").string()});
  const auto st = c.wait(20s);
  ASSERT_TRUE(st.has_value()) << c.output();
  EXPECT_EQ(exit_code(*st), 2) << c.output();
  EXPECT_TRUE(has(c.output(), "transport tcp://0.0.0.0:*: CURVE is required")) << c.output();
  EXPECT_TRUE(has(c.output(), "--curve-secret-key")) << c.output();
}

TEST(CurveProcesses, KeygenRefusesToOverwrite) {
  const auto dir = fresh_dir("curve-keygen");
  const RemoveIfPassed cleanup{dir};
  const std::string pub = keygen(dir, "k");
  EXPECT_EQ(pub.size(), 40u) << pub;
  Child again({bin("crashlink"), "keygen", "--out", (dir / "k").string()});
  const auto st = again.wait(20s);
  ASSERT_TRUE(st.has_value());
  EXPECT_EQ(exit_code(*st), 2) << again.output();
  EXPECT_TRUE(has(again.output(), "k.key exists already")) << again.output();
  EXPECT_EQ(keygen(dir, "k2").size(), 40u);
}

}  // namespace
