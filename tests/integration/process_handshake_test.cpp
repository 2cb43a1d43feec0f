// Refusals at the door of a `layer` run (docs/design.md §3): a daemon of another protocol version
// and a daemon given another scenario file are refused with a message giving both values; bytes
// that are not protocol messages (a ZeroMQ peer sending junk, a plain TCP socket writing junk) are
// rejected without a crash. In every case the coordinator goes on and the real daemons then
// complete the run. Runs over tcp (ephemeral port read back), ipc and inproc (threads).
#include <arpa/inet.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cstdio>
#include <string>
#include <thread>

#include "coordinator/coordinator_run.h"
#include "core/exit_codes.h"
#include "process_test_support.h"
#include "proto/protocol_version.h"
#include "solver/daemon/daemon.h"
#include "solver/io/scenario_hash.h"
#include "transport/daemon_link.h"
#include "transport/dealer.h"
#include "transport/errors.h"

using namespace crashlink;
using namespace crashlink::proc_test;
using transport::Scheme;

namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A coordinator and daemons as processes (tcp, ipc) or as threads of this process (inproc).
class Pieces {
 public:
  Pieces(Scheme scheme, std::filesystem::path dir, std::string scenario)
      : scheme_(scheme), dir_(std::move(dir)), scenario_(std::move(scenario)) {}
  ~Pieces() {
    for (auto& t : threads_) {
      if (t.joinable()) t.join();
    }
    if (coordinator_thread_.joinable()) coordinator_thread_.join();
    if (log_ != nullptr) std::fclose(log_);
  }

  const std::string& endpoint() const { return endpoint_; }
  std::filesystem::path out() const { return dir_ / "out"; }

  void start_coordinator() {
    if (scheme_ != Scheme::inproc) {
      coordinator_ = start_coordinator_process();
      return;
    }
    log_ = std::tmpfile();
    options_.bind = transport::local_endpoint(Scheme::inproc, "handshake");
    options_.scenario = scenario_;
    options_.out_dir = out().string();
    options_.run.common_step = false;
    options_.in_process = true;
    options_.log = log_;
    options_.session.heartbeat_interval = 100ms;
    options_.session.peer_timeout = 1000ms;
    options_.join_timeout = 20s;
    endpoint_ = options_.bind;
    coordinator_thread_ = std::thread([this] { result_ = coordinator::run_coordinator(options_); });
  }

  /// Starts a daemon for `domain` reading `scenario` (default: the run's); returns its index.
  std::size_t start_daemon(const std::string& domain, const std::string& scenario = {}) {
    const std::string file = scenario.empty() ? scenario_ : scenario;
    const std::size_t k = daemon_results_.size();
    daemon_results_.emplace_back();
    if (scheme_ != Scheme::inproc) {
      daemons_.push_back(start_solver(endpoint_, domain, file, out(), {"--step-safety", "0.9"}));
      return k;
    }
    daemons_.emplace_back();
    threads_.emplace_back([this, domain, file, k] {
      daemon::DaemonOptions d;
      d.endpoint = endpoint_;
      d.domain = domain;
      d.scenario = file;
      d.out_dir = out().string();
      d.in_process = true;
      d.step_safety = 0.9;
      d.session.heartbeat_interval = 100ms;
      d.session.peer_timeout = 1000ms;
      daemon_results_[k] = daemon::run_daemon(d);
    });
    return k;
  }

  /// Exit code and output of daemon k once it has ended.
  std::pair<int, std::string> wait_daemon(std::size_t k) {
    if (scheme_ != Scheme::inproc) {
      const auto st = daemons_[k]->wait(30s);
      return {st ? exit_code(*st) : -999, daemons_[k]->output()};
    }
    if (threads_[k].joinable()) threads_[k].join();
    return {daemon_results_[k].exit_code, daemon_results_[k].message};
  }

  /// Exit code and log of the coordinator once it has ended.
  std::pair<int, std::string> wait_coordinator() {
    if (scheme_ != Scheme::inproc) {
      const auto st = coordinator_->wait(30s);
      return {st ? exit_code(*st) : -999, coordinator_->output()};
    }
    coordinator_thread_.join();
    std::string log;
    std::rewind(log_);
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, log_)) > 0) log.append(buf, n);
    return {result_.exit_code, log + result_.message};
  }

 private:
  std::unique_ptr<Child> start_coordinator_process() {
    return proc_test::start_coordinator(bind_endpoint(scheme_, dir_), scenario_, out(), "multi",
                                        endpoint_);
  }

  Scheme scheme_;
  std::filesystem::path dir_;
  std::string scenario_, endpoint_;
  std::unique_ptr<Child> coordinator_;
  std::vector<std::unique_ptr<Child>> daemons_;
  coordinator::CoordinatorOptions options_;
  coordinator::CoordinatorResult result_;
  std::thread coordinator_thread_;
  std::vector<std::thread> threads_;
  std::vector<daemon::DaemonResult> daemon_results_;
  std::FILE* log_ = nullptr;
};

class Handshake : public ::testing::TestWithParam<Scheme> {
 protected:
  std::string name() const { return std::string(transport::scheme_name(GetParam())); }

  /// After the refusals: the real daemons run the scenario to its end, all exit 0.
  static void expect_run_completes(Pieces& p) {
    const auto fine = p.start_daemon("fine");
    const auto coarse = p.start_daemon("coarse");
    for (const auto k : {fine, coarse}) {
      const auto [code, out] = p.wait_daemon(k);
      EXPECT_EQ(code, 0) << out;
    }
    const auto [code, log] = p.wait_coordinator();
    EXPECT_EQ(code, 0) << log;
  }
};

}  // namespace

TEST_P(Handshake, OtherProtocolVersionIsRefusedWithBothVersions) {
  const auto dir = fresh_dir("version-" + name());
  const RemoveIfPassed cleanup{dir};
  Pieces p(GetParam(), dir, write_file(dir / "bar.yaml", bar_yaml(5.0e-4)));
  p.start_coordinator();
  auto hello = transport::daemon_hello("rogue", io::scenario_hash((dir / "bar.yaml").string()));
  const std::uint32_t theirs = wire::kProtocolVersion + 1;
  hello.set_protocol_version(theirs);
  transport::SessionOptions fast;
  fast.heartbeat_interval = 100ms;
  fast.peer_timeout = 1000ms;
  fast.handshake_timeout = 10s;
  try {
    transport::DaemonLink link(p.endpoint(), hello, fast);
    ADD_FAILURE() << "a daemon of protocol version " << theirs << " was accepted";
  } catch (const transport::RemoteError& e) {
    const std::string what = e.what();
    std::printf("[measured] %s: refusal of protocol version %u: %s\n", name().c_str(), theirs,
                what.c_str());
    EXPECT_EQ(e.code(), wire::ERROR_CODE_VERSION_MISMATCH);
    EXPECT_TRUE(has(what, fmt::format("version {}", theirs))) << what;
    EXPECT_TRUE(has(what, fmt::format("version {}", wire::kProtocolVersion))) << what;
  }
  expect_run_completes(p);
}

TEST_P(Handshake, OtherScenarioFileIsRefusedWithBothHashes) {
  const auto dir = fresh_dir("hash-" + name());
  const RemoveIfPassed cleanup{dir};
  const std::string ours = write_file(dir / "bar.yaml", bar_yaml(5.0e-4));
  const std::string other = write_file(dir / "other.yaml", bar_yaml(6.0e-4));
  Pieces p(GetParam(), dir, ours);
  p.start_coordinator();
  const auto k = p.start_daemon("fine", other);
  const auto [code, out] = p.wait_daemon(k);
  std::printf("[measured] %s: daemon with another scenario: exit %d: %s\n", name().c_str(), code,
              out.c_str());
  EXPECT_EQ(code, kExitInput) << out;
  EXPECT_TRUE(has(out, io::scenario_hash(ours))) << out;
  EXPECT_TRUE(has(out, io::scenario_hash(other))) << out;
  EXPECT_TRUE(has(out, "same scenario file")) << out;
  expect_run_completes(p);
}

TEST_P(Handshake, GarbageIsRejectedAndTheRunGoesOn) {
  const auto dir = fresh_dir("junk-" + name());
  const RemoveIfPassed cleanup{dir};
  Pieces p(GetParam(), dir, write_file(dir / "bar.yaml", bar_yaml(5.0e-4)));
  p.start_coordinator();
  {
    // A ZeroMQ peer that speaks no crashlink: junk, then an empty message.
    transport::Dealer junk(p.endpoint(), "junk");
    junk.send_raw(std::string("\xff\xfe\x00 not a protocol buffer", 26));
    junk.send_raw("");
    const auto answer = junk.receive(5s);
    ASSERT_TRUE(answer.has_value()) << "no answer to junk";
    EXPECT_TRUE(answer->ok() && answer->envelope.has_error());
  }
  if (GetParam() == Scheme::tcp) {
    // A plain TCP client writing bytes that are not even ZMTP.
    const auto colon = p.endpoint().rfind(':');
    const int port = std::stoi(p.endpoint().substr(colon + 1));
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    const std::string bytes(4096, '\x42');
    EXPECT_GT(write(fd, bytes.data(), bytes.size()), 0);
    close(fd);
  }
  expect_run_completes(p);
}

TEST_P(Handshake, MismatchedRegisterStopsTheRunNamingDomainAndNode) {
  const auto dir = fresh_dir("register-" + name());
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(5.0e-4));
  Pieces p(GetParam(), dir, scenario);
  p.start_coordinator();
  transport::SessionOptions fast;
  fast.heartbeat_interval = 100ms;
  fast.peer_timeout = 1000ms;
  fast.handshake_timeout = 10s;
  // Domain 'fine' with the right hash registers a J node its cut does not have.
  transport::DaemonLink link(p.endpoint(),
                             transport::daemon_hello("fine", io::scenario_hash(scenario)), fast);
  wire::Envelope e;
  auto* r = e.mutable_registration();
  r->set_stable_step_ticks(1'000'000'000);
  auto* li = r->add_layer_interfaces();
  li->set_index(0);
  li->set_fine_side(true);
  li->add_j_node_ids(987654);
  li->add_masses_kg(0.0);
  for (int d = 0; d < 3; ++d) li->add_positions_m(0.0);
  link.send(e);
  try {
    while (link.receive(5s)) {
    }
    ADD_FAILURE() << "no Error after a mismatched Register";
  } catch (const transport::RemoteError& x) {
    const std::string what = x.what();
    std::printf("[measured] %s: mismatched Register: %s\n", name().c_str(), what.c_str());
    EXPECT_EQ(x.code(), wire::ERROR_CODE_MODEL);
    EXPECT_TRUE(has(what, "'fine'")) << what;
    EXPECT_TRUE(has(what, "987654")) << what;
  }
  const auto [code, log] = p.wait_coordinator();
  EXPECT_EQ(code, kExitInput) << log;
  EXPECT_TRUE(has(log, "987654")) << log;
}

INSTANTIATE_TEST_SUITE_P(Transports, Handshake,
                         ::testing::Values(Scheme::tcp, Scheme::ipc, Scheme::inproc),
                         scheme_test_name);
