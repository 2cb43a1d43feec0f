// A `layer` run across a real (virtual) network (issue #6): the coordinator and each daemon in
// their own network namespace with their own address, so every message crosses a veth link and a
// bridge instead of the loopback device.
//
//   namespace cl-<pid>-c: bridge br0 10.250.1.1/24 (the coordinator binds tcp://10.250.1.1:*),
//                         veth ends va, vb enslaved to br0
//   namespace cl-<pid>-a: eth0 10.250.1.2/24 (peer of va): daemon of the first domain
//   namespace cl-<pid>-b: eth0 10.250.1.3/24 (peer of vb): daemon of the second domain
//
// Only namespaces this test creates are touched (the links are created inside them; deleting a
// namespace deletes its links); the host's interfaces and routes are never changed. A guard
// deletes the namespaces at the end of every path (also on failure); namespaces left by an earlier
// test process that was killed (cl-<pid>-* with <pid> no longer alive) are deleted first.
// Without `ip` (iproute2) or the right to create a namespace (root / CAP_SYS_ADMIN), the tests
// are skipped with the reason. Every spawned process has a hard timeout (killed after it).
//
// 1. End to end: a two-domain run (bar, multi at H/h = 2; plate, multi at the steps the daemons
//    propose) across the namespaces, gathered with `crashlink gather`, against the same run over
//    tcp loopback in this namespace: displacements of every node at every state, the energy
//    history (glstat) and the coordinator's link work must be bit-identical (the scheme is
//    deterministic: the messages carry packed doubles and the result does not depend on when
//    they arrive).
// 2. Network cut: the first daemon's link is brought down mid-run; the coordinator must name the
//    silent domain, the cut daemon the coordinator, the other daemon the silent domain; everybody
//    exits non-zero within the peer timeout + margin, and the files written so far open.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/exit_codes.h"
#include "process_test_support.h"
#include "solver/io/result_reader.h"
#include "transport/curve_keygen.h"

using namespace crashlink;
using namespace crashlink::proc_test;

namespace {

constexpr const char* kCoordinatorAddress = "10.250.1.1";

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The first line of `text` that contains `part` ("" if none).
std::string line_with(const std::string& text, const std::string& part) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (has(line, part)) return line;
  }
  return {};
}

double seconds_since(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double>(t1 - t0).count();
}

/// The `ip` executable of iproute2 ("" if none).
std::string ip_binary() {
  for (const char* p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"}) {
    if (::access(p, X_OK) == 0) return p;
  }
  return {};
}

struct CommandResult {
  int code = -999;  ///< exit code; -999: killed after the timeout
  std::string output;
};

/// Runs argv (absolute path first) with its output captured; killed after `timeout`.
CommandResult run(const std::vector<std::string>& argv,
                  std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
  Child c(argv);
  const auto st = c.wait(timeout);
  CommandResult r;
  if (st) r.code = exit_code(*st);
  // Child's reader thread may still be appending: wait for the end of the output.
  c.wait_for_output("\x01never\x01", std::chrono::milliseconds(200));
  r.output = c.output();
  return r;
}

/// Three namespaces joined by a bridge (see the header); deleted on destruction.
class Namespaces {
 public:
  Namespaces() {
    ip_ = ip_binary();
    if (ip_.empty()) {
      reason_ = "no `ip` executable (iproute2) in /usr/sbin, /sbin, /usr/bin, /bin";
      return;
    }
    const std::string prefix = "cl-" + std::to_string(::getpid()) + "-";
    coordinator_ = prefix + "c";
    daemons_ = {prefix + "a", prefix + "b"};
    remove_stale();
    const std::vector<std::vector<std::string>> steps = [&] {
      std::vector<std::vector<std::string>> s;
      for (const auto& ns : all()) s.push_back({"netns", "add", ns});
      s.push_back({"-n", coordinator_, "link", "set", "lo", "up"});
      s.push_back({"-n", coordinator_, "link", "add", "br0", "type", "bridge"});
      s.push_back({"-n", coordinator_, "addr", "add", std::string(kCoordinatorAddress) + "/24",
                   "dev", "br0"});
      s.push_back({"-n", coordinator_, "link", "set", "br0", "up"});
      for (std::size_t k = 0; k < daemons_.size(); ++k) {
        const std::string v = k == 0 ? "va" : "vb";
        s.push_back({"-n", coordinator_, "link", "add", v, "type", "veth", "peer", "name", "eth0",
                     "netns", daemons_[k]});
        s.push_back({"-n", coordinator_, "link", "set", v, "master", "br0"});
        s.push_back({"-n", coordinator_, "link", "set", v, "up"});
        s.push_back({"-n", daemons_[k], "link", "set", "lo", "up"});
        s.push_back({"-n", daemons_[k], "addr", "add", daemon_address(k) + "/24", "dev", "eth0"});
        s.push_back({"-n", daemons_[k], "link", "set", "eth0", "up"});
      }
      // `ip netns exec` also needs a mount namespace (sysfs remount): probe it once, so that a
      // container allowed to create namespaces but not to enter them skips instead of failing.
      for (const auto& ns : all()) s.push_back({"netns", "exec", ns, "true"});
      return s;
    }();
    for (const auto& args : steps) {
      const auto r = ip(args);
      if (r.code != 0) {
        std::string cmd = ip_;
        for (const auto& a : args) cmd.append(" ").append(a);
        reason_ = "`" + cmd + "` failed (exit " + std::to_string(r.code) + ", euid " +
                  std::to_string(::geteuid()) +
                  "; creating network namespaces needs root or CAP_SYS_ADMIN + CAP_NET_ADMIN): " +
                  r.output;
        while (!reason_.empty() && reason_.back() == '\n') reason_.pop_back();
        return;
      }
    }
    ok_ = true;
  }
  Namespaces(const Namespaces&) = delete;
  Namespaces& operator=(const Namespaces&) = delete;
  ~Namespaces() {
    if (ip_.empty()) return;
    // Deleting a namespace deletes its links (the veth pairs with them); a process still inside
    // would keep it alive: the callers end their children first.
    for (const auto& ns : all()) ip({"netns", "delete", ns});
  }

  bool ok() const { return ok_; }
  const std::string& reason() const { return reason_; }
  const std::string& coordinator() const { return coordinator_; }
  const std::string& daemon(std::size_t k) const { return daemons_.at(k); }
  static std::string daemon_address(std::size_t k) { return "10.250.1." + std::to_string(2 + k); }

  /// argv run inside namespace `ns` (`ip netns exec` execs it: the pid is the program's).
  std::vector<std::string> in(const std::string& ns, std::vector<std::string> argv) const {
    std::vector<std::string> a{ip_, "netns", "exec", ns};
    for (auto& s : argv) a.push_back(std::move(s));
    return a;
  }

  CommandResult ip(const std::vector<std::string>& args) const {
    std::vector<std::string> a{ip_};
    a.insert(a.end(), args.begin(), args.end());
    return run(a);
  }

  /// Bytes received and sent on eth0 of daemon k's namespace (-1 if unreadable).
  std::pair<long long, long long> traffic(std::size_t k) const {
    const auto r = ip({"-n", daemons_.at(k), "-s", "link", "show", "eth0"});
    std::istringstream in(r.output);
    std::string line;
    long long rx = -1, tx = -1;
    while (std::getline(in, line)) {
      const bool is_rx = has(line, "RX:"), is_tx = has(line, "TX:");
      if (!is_rx && !is_tx) continue;
      std::string numbers;
      if (!std::getline(in, numbers)) break;
      long long v = -1;
      std::istringstream(numbers) >> v;
      (is_rx ? rx : tx) = v;
    }
    return {rx, tx};
  }

 private:
  std::vector<std::string> all() const { return {coordinator_, daemons_[0], daemons_[1]}; }

  /// Deletes cl-<pid>-{c,a,b} namespaces whose test process no longer exists (a killed run).
  void remove_stale() const {
    const auto r = ip({"netns", "list"});
    std::istringstream in(r.output);
    std::string line;
    const std::regex mine(R"(^(cl-([0-9]+)-[abc])(\s.*)?$)");
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_match(line, m, mine)) continue;
      const long pid = std::stol(m[2].str());
      if (pid == ::getpid()) continue;
      if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
        std::printf("[netns] removing stale namespace %s (process %ld is gone)\n",
                    m[1].str().c_str(), pid);
        ip({"netns", "delete", m[1].str()});
      }
    }
  }

  std::string ip_, reason_, coordinator_;
  std::vector<std::string> daemons_;
  bool ok_ = false;
};

/// A coupled run's processes: the coordinator (in namespace `cns` unless empty) and one daemon per
/// domain (namespace dns[k] unless empty).
struct Pieces {
  std::unique_ptr<Child> coordinator;
  std::vector<std::unique_ptr<Child>> daemons;
  std::string endpoint;
};

std::vector<std::string> solver_argv(const std::string& endpoint, const std::string& domain,
                                     const std::string& scenario, const std::filesystem::path& out,
                                     const std::vector<std::string>& extra,
                                     const std::vector<std::string>& session) {
  std::vector<std::string> a = solver_args(endpoint, domain, scenario, out);
  a.insert(a.end(), session.begin(), session.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

/// Starts the coordinator (bound to `bind`, real endpoint read back) and the daemons.
/// `wrap(k, argv)`: the argv of piece k (0: coordinator, 1..: daemons) as started.
template <class Wrap>
void start(Pieces& p, const Wrap& wrap, const std::string& bind, const std::string& scenario,
           const std::filesystem::path& out,
           const std::vector<std::pair<std::string, std::vector<std::string>>>& domains,
           const std::vector<std::string>& session) {
  auto argv = coordinator_args(bind, scenario, out, "multi");
  argv.insert(argv.end(), session.begin(), session.end());
  p.coordinator = std::make_unique<Child>(wrap(0, std::move(argv)));
  ASSERT_TRUE(p.coordinator->wait_for_output(" for ", std::chrono::seconds(15)))
      << p.coordinator->output();
  p.endpoint = p.coordinator->between("listening on ", " for ");
  ASSERT_FALSE(p.endpoint.empty()) << p.coordinator->output();
  for (std::size_t k = 0; k < domains.size(); ++k) {
    p.daemons.push_back(
        std::make_unique<Child>(wrap(k + 1, solver_argv(p.endpoint, domains[k].first, scenario, out,
                                                        domains[k].second, session))));
  }
}

/// Waits for every piece (hard limit `limit` each); true if all exited 0.
bool finish(Pieces& p, std::chrono::seconds limit) {
  bool ok = true;
  for (auto& d : p.daemons) {
    const auto st = d->wait(limit);
    EXPECT_TRUE(st && exit_code(*st) == 0) << d->output();
    ok = ok && st && exit_code(*st) == 0;
  }
  const auto st = p.coordinator->wait(limit);
  EXPECT_TRUE(st && exit_code(*st) == 0) << p.coordinator->output();
  return ok && st && exit_code(*st) == 0;
}

CommandResult gather(const std::string& scenario, const std::filesystem::path& out) {
  return run({bin("crashlink"), "gather", scenario, "--out", out.string()},
             std::chrono::seconds(60));
}

/// Bit-for-bit comparison of two result files: node ids, every state's time and displacement,
/// every glstat row. Returns the number of differing values (0: identical), counting a
/// structural mismatch as one; `what` says what was compared.
std::size_t differences(const std::string& a, const std::string& b, std::string& what) {
  io::ResultReader ra(a), rb(b);
  std::size_t diff = 0;
  if (ra.node_ids() != rb.node_ids()) ++diff;
  const std::size_t states = ra.state_count();
  if (states != rb.state_count() || states == 0) ++diff;
  std::size_t values = 0;
  for (std::size_t k = 0; k < std::min(states, rb.state_count()); ++k) {
    const auto sa = ra.state(k), sb = rb.state(k);
    if (sa.time_s != sb.time_s || sa.displacement_m.size() != sb.displacement_m.size()) {
      ++diff;
      continue;
    }
    for (std::size_t i = 0; i < sa.displacement_m.size(); ++i) {
      diff += sa.displacement_m[i] != sb.displacement_m[i];
    }
    values += sa.displacement_m.size();
  }
  const auto ga = ra.glstat(), gb = rb.glstat();
  if (ga.size() != gb.size() || ga.empty()) ++diff;
  for (std::size_t i = 0; i < std::min(ga.size(), gb.size()); ++i) {
    const auto& x = ga[i];
    const auto& y = gb[i];
    diff += x.time_s != y.time_s;
    diff += x.kinetic_energy_J != y.kinetic_energy_J;
    diff += x.internal_energy_J != y.internal_energy_J;
    diff += x.hourglass_energy_J != y.hourglass_energy_J;
    diff += x.contact_energy_J != y.contact_energy_J;
    diff += x.external_work_J != y.external_work_J;
    diff += x.total_energy_J != y.total_energy_J;
    diff += x.energy_balance_error != y.energy_balance_error;
  }
  what = std::to_string(states) + " states x " + std::to_string(ra.node_ids().size()) + " nodes (" +
         std::to_string(values) + " displacement values), " + std::to_string(ga.size()) +
         " glstat rows";
  return diff;
}

struct Case {
  std::string label;
  std::string yaml;
  std::vector<std::pair<std::string, std::vector<std::string>>> domains;
};

Case bar_case() {
  return {"bar",
          bar_yaml(6.0e-3),
          {{"fine", {"--max-step", "1e-6", "--step-safety", "1"}},
           {"coarse", {"--max-step", "2e-6", "--step-safety", "1"}}}};
}

Case plate_case() {
  return {"plate",
          plate_yaml(4.0e-3),
          {{"left", {"--step-safety", "0.9"}}, {"right", {"--step-safety", "0.9"}}}};
}

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.label;
}

std::string case_name(const ::testing::TestParamInfo<Case>& p) {
  return p.param.label;
}

class AcrossNamespaces : public ::testing::TestWithParam<Case> {};

/// The coordinator binds a non-loopback address, so CURVE is on (docs/processes.md, "Security
/// (CURVE)"): one key pair for every piece, its public key the only authorized one. The loopback
/// runs get the same flags and use no CURVE (not forced).
std::vector<std::string> with_curve(std::vector<std::string> session,
                                    const std::filesystem::path& dir) {
  const auto keys = transport::write_curve_keypair((dir / "run").string(), false);
  for (const std::string& a :
       {std::string("--curve-secret-key"), keys.secret_file, std::string("--curve-server-key"),
        keys.public_file, std::string("--curve-authorized-keys"), keys.public_file}) {
    session.push_back(a);
  }
  return session;
}

}  // namespace

TEST_P(AcrossNamespaces, MultiRunEqualsLoopbackRunToTheBit) {
  const Case& c = GetParam();
  Namespaces net;
  if (!net.ok()) GTEST_SKIP() << "network namespaces not available: " << net.reason();
  const auto dir = fresh_dir("netns-" + c.label);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / (c.label + ".yaml"), c.yaml);
  const auto out_net = dir / "netns", out_local = dir / "local";
  const auto session = with_curve(fast_session_args(), dir);

  // Across the namespaces: the coordinator on the bridge's address, each daemon behind its veth.
  double wall_net = 0.0, wall_local = 0.0;
  {
    Pieces p;
    const auto wrap = [&](std::size_t k, std::vector<std::string> argv) {
      return net.in(k == 0 ? net.coordinator() : net.daemon(k - 1), std::move(argv));
    };
    const auto t0 = Clock::now();
    ASSERT_NO_FATAL_FAILURE(start(p, wrap, "tcp://" + std::string(kCoordinatorAddress) + ":*",
                                  scenario, out_net, c.domains, session));
    EXPECT_TRUE(has(p.endpoint, kCoordinatorAddress)) << p.endpoint;
    ASSERT_TRUE(finish(p, std::chrono::seconds(50)));
    wall_net = seconds_since(t0, Clock::now());
    // The daemons reach each other's lanes on their own addresses, CURVE on (docs/processes.md
    // "Lanes"): the vectors skip the coordinator across namespaces too.
    EXPECT_TRUE(has(p.coordinator->output(), "layer vectors daemon to daemon (lanes)"))
        << p.coordinator->output();
    for (std::size_t k = 0; k < c.domains.size(); ++k) {
      const auto [rx, tx] = net.traffic(k);
      std::printf(
          "[measured] netns %s: daemon '%s' at %s: eth0 received %lld bytes, sent %lld bytes\n",
          c.label.c_str(), c.domains[k].first.c_str(), Namespaces::daemon_address(k).c_str(), rx,
          tx);
      EXPECT_GT(rx, 10000) << "the messages did not cross the veth link";
      EXPECT_GT(tx, 10000) << "the messages did not cross the veth link";
    }
  }
  // The same over tcp loopback in this namespace.
  {
    Pieces p;
    const auto wrap = [](std::size_t, std::vector<std::string> argv) { return argv; };
    const auto t0 = Clock::now();
    ASSERT_NO_FATAL_FAILURE(
        start(p, wrap, "tcp://127.0.0.1:*", scenario, out_local, c.domains, session));
    ASSERT_TRUE(finish(p, std::chrono::seconds(50)));
    wall_local = seconds_since(t0, Clock::now());
  }
  for (const auto& out : {out_net, out_local}) {
    const auto g = gather(scenario, out);
    ASSERT_EQ(g.code, 0) << g.output;
  }

  std::string what;
  for (const auto& [domain, extra] : c.domains) {
    const std::string f = "domains/" + domain + ".h5";
    EXPECT_EQ(differences((out_net / f).string(), (out_local / f).string(), what), 0u)
        << f << ": " << what;
  }
  const std::size_t d =
      differences((out_net / "result.h5").string(), (out_local / "result.h5").string(), what);
  EXPECT_EQ(d, 0u) << "result.h5 across namespaces differs from the loopback run: " << what;
  // The coordinator's interface history (its link work) too: /coupling/<fine>-<coarse>.
  std::string iface;
  std::vector<double> w_net, w_local;
  for (const auto& [x, y] : {std::pair{c.domains[0].first, c.domains[1].first},
                             std::pair{c.domains[1].first, c.domains[0].first}}) {
    iface = "/coupling/" + x + "-" + y + "/link_work";
    w_net = read_doubles((out_net / "coordinator.h5").string(), iface);
    if (!w_net.empty()) break;
  }
  w_local = read_doubles((out_local / "coordinator.h5").string(), iface);
  EXPECT_FALSE(w_net.empty()) << iface;
  EXPECT_EQ(w_net, w_local) << iface;
  std::printf(
      "[measured] netns %s (multi, tcp): across namespaces %.2f s wall, loopback %.2f s; "
      "gathered result.h5: %s; %zu values differ; link work rows %zu, last %.9e J (%s)\n",
      c.label.c_str(), wall_net, wall_local, what.c_str(), d, w_net.size(),
      w_net.empty() ? 0.0 : w_net.back(), w_net == w_local ? "identical" : "DIFFERENT");
}

INSTANTIATE_TEST_SUITE_P(Scenarios, AcrossNamespaces, ::testing::Values(bar_case(), plate_case()),
                         case_name);

// The first daemon's link goes down mid-run (`ip -n NS link set eth0 down`: its packets go
// nowhere, nothing is reset). Heartbeat 100 ms, peer timeout 1 s: the coordinator finds the domain
// silent after ~1 s and tells the other daemon; the cut daemon finds the coordinator silent.
TEST(NetworkCut, LinkDownIsDetectedOnBothSides) {
  Namespaces net;
  if (!net.ok()) GTEST_SKIP() << "network namespaces not available: " << net.reason();
  const auto dir = fresh_dir("netns-cut");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario =
      write_file(dir / "bar.yaml", stopped_early(bar_yaml(10.0)));  // minutes long
  const auto out = dir / "out";
  const std::vector<std::pair<std::string, std::vector<std::string>>> domains{
      {"fine", {"--step-safety", "0.9"}}, {"coarse", {"--step-safety", "0.9"}}};
  Pieces p;
  const auto wrap = [&](std::size_t k, std::vector<std::string> argv) {
    return net.in(k == 0 ? net.coordinator() : net.daemon(k - 1), std::move(argv));
  };
  ASSERT_NO_FATAL_FAILURE(start(p, wrap, "tcp://" + std::string(kCoordinatorAddress) + ":*",
                                scenario, out, domains, with_curve(fast_session_args(), dir)));
  ASSERT_TRUE(p.coordinator->wait_for_output("steps:", std::chrono::seconds(20)))
      << p.coordinator->output();
  // Mid-run: both daemons stepping and flushing history for a while.
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  for (const auto& [d, x] : domains) {
    ASSERT_TRUE(std::filesystem::exists(out / "domains" / (d + ".h5"))) << d;
  }
  const auto cut = net.ip({"-n", net.daemon(0), "link", "set", "eth0", "down"});
  const auto t0 = Clock::now();
  ASSERT_EQ(cut.code, 0) << cut.output;

  auto ends = [&](Child& c) -> std::pair<int, double> {
    const auto st = c.wait(std::chrono::seconds(6));  // peer timeout 1 s + linger + margin
    if (!st) return {-999, 1e9};
    return {exit_code(*st), seconds_since(t0, c.exited_at())};
  };
  const auto [cc, ct] = ends(*p.coordinator);
  const auto [fc, ft] = ends(*p.daemons[0]);
  const auto [oc, ot] = ends(*p.daemons[1]);
  std::printf(
      "[measured] network cut (link of daemon 'fine' down, heartbeat 100 ms, peer timeout 1 s): "
      "coordinator exit %d after %.3f s, daemon 'coarse' exit %d after %.3f s, cut daemon 'fine' "
      "exit %d after %.3f s\n",
      cc, ct, oc, ot, fc, ft);
  const std::string clog = p.coordinator->output(), flog = p.daemons[0]->output(),
                    olog = p.daemons[1]->output();
  EXPECT_EQ(cc, kExitPeer) << clog;
  EXPECT_EQ(fc, kExitPeer) << flog;
  EXPECT_EQ(oc, kExitPeer) << olog;
  EXPECT_GE(ct, 0.9);  // not before the peer timeout
  EXPECT_LE(ct, 5.0);
  EXPECT_LE(ot, 5.0);
  EXPECT_GE(ft, 0.9);
  EXPECT_LE(ft, 5.0);
  EXPECT_TRUE(has(clog, "domain 'fine'") && has(clog, "silent")) << clog;
  EXPECT_TRUE(has(flog, "the coordinator") && has(flog, kCoordinatorAddress)) << flog;
  EXPECT_TRUE(has(olog, "'fine'")) << olog;
  std::printf(
      "[measured]   coordinator: %s\n[measured]   daemon 'coarse': %s\n[measured]   "
      "daemon 'fine': %s\n",
      line_with(clog, "silent").c_str(), line_with(olog, "'fine'").c_str(),
      line_with(flog, "the coordinator").c_str());

  // Everything written so far opens: each daemon's file, and the gathered result.h5.
  for (const auto& [d, x] : domains) {
    io::ResultReader r((out / "domains" / (d + ".h5")).string());
    EXPECT_FALSE(r.glstat().empty()) << d;
  }
  const auto g = gather(scenario, out);
  EXPECT_EQ(g.code, 0) << g.output;
  io::ResultReader gathered((out / "result.h5").string());
  EXPECT_FALSE(gathered.glstat().empty());
  std::printf("[measured]   %s", g.output.c_str());
}
