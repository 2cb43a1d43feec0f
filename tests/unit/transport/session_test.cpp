// Session layer (docs/design.md §3): handshake, refusals with both values, several daemons in
// threads, garbage, silent peers on both sides, Bye and Error. Every suite runs on every transport;
// every wait is bounded.
#include "transport/session.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "proto/protocol_version.h"
#include "transport/dealer.h"
#include "transport/errors.h"
#include "transport_test_support.h"

namespace crashlink::transport::test {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kHash = "5ca1ab1e";

class Session : public ::testing::TestWithParam<Scheme> {
 protected:
  static CoordinatorConfig config(std::vector<std::string> domains) {
    CoordinatorConfig c;
    c.scenario_hash = kHash;
    c.domains = std::move(domains);
    c.ticks_per_second = 1'000'000'000'000'000;
    c.options = fast_options();
    return c;
  }
  std::unique_ptr<CoordinatorLink> coordinator = std::make_unique<CoordinatorLink>(
      local_endpoint(GetParam(), "session"), config({"car", "wiper", "head"}));
};

/// The coordinator's next message within 5 s.
Incoming next_incoming(CoordinatorLink& link) {
  auto in = link.poll(5s);
  if (!in) {
    ADD_FAILURE() << "coordinator received nothing within 5 s";
    return {};
  }
  return std::move(*in);
}

wire::Envelope free_state(std::int64_t time, std::vector<double> a) {
  wire::Envelope e;
  e.mutable_free_state()->set_time_ticks(time);
  e.mutable_free_state()->mutable_accelerations_m_s2()->Add(a.begin(), a.end());
  return e;
}

/// The refusal a Hello gets, as the daemon sees it.
RemoteError refusal(CoordinatorLink& coordinator, const wire::Hello& hello) {
  try {
    connect_daemon(coordinator, hello);
  } catch (const RemoteError& e) {
    return e;
  }
  ADD_FAILURE() << "Hello of '" << hello.domain() << "' was accepted";
  return RemoteError(wire::Error{});
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_P(Session, HandshakeThenExchangeThenBye) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  EXPECT_EQ(car.coordinator_hello().ticks_per_second(), 1'000'000'000'000'000);
  EXPECT_EQ(car.coordinator_hello().protocol_version(), wire::kProtocolVersion);
  EXPECT_TRUE(coordinator->joined("car"));
  EXPECT_EQ(coordinator->missing(), (std::vector<std::string>{"wiper", "head"}));

  car.send(free_state(10, {1.0, -0.0, 3.0}));
  const Incoming in = next_incoming(*coordinator);
  EXPECT_EQ(in.domain, "car");
  ASSERT_TRUE(in.envelope.has_free_state());
  EXPECT_EQ(in.envelope.free_state().time_ticks(), 10);

  wire::Envelope answer;
  answer.mutable_correction()->set_time_ticks(10);
  coordinator->send("car", answer);
  const auto got = car.receive(5s);
  ASSERT_TRUE(got && got->has_correction());
  EXPECT_EQ(got->correction().time_ticks(), 10);

  car.bye("end time reached");
  EXPECT_FALSE(car.open());
  const Incoming bye = next_incoming(*coordinator);
  EXPECT_TRUE(bye.envelope.has_bye());
  EXPECT_EQ(bye.envelope.bye().reason(), "end time reached");
  EXPECT_FALSE(coordinator->joined("car"));
  EXPECT_THROW(coordinator->send("car", answer), TransportError);
}

// n daemons in their own threads: Register -> Setup, then rounds of FreeState -> Correction
// (the coordinator doubles the accelerations; the daemons check every bit), then Bye.
void run_daemons(Scheme scheme, int n) {
  SCOPED_TRACE(fmt::format("{} daemons", n));
  const std::vector<std::string> names = {"car", "wiper", "head"};
  auto cfg = CoordinatorConfig{kHash, {names.begin(), names.begin() + n}, 1000, fast_options()};
  CoordinatorLink coordinator(local_endpoint(scheme, "multi"), cfg);
  constexpr int kRounds = 50;
  std::vector<std::string> failures(static_cast<std::size_t>(n));
  std::vector<std::thread> threads;
  for (int k = 0; k < n; ++k) {
    threads.emplace_back([&, k] {
      std::string& failure = failures[static_cast<std::size_t>(k)];
      try {
        DaemonLink link(coordinator.endpoint(), daemon_hello(names[k], kHash), fast_options());
        wire::Envelope reg;
        reg.mutable_registration()->add_node_ids(k);
        link.send(reg);
        auto setup = link.receive(5s);
        if (!setup || !setup->has_setup() || setup->setup().summed_masses_kg(0) != 0.5 + k) {
          failure = "no Setup";
          return;
        }
        for (int i = 0; i < kRounds; ++i) {
          const auto a = tricky_doubles(30, k + 1.0 + i);
          link.send(free_state(i, a));
          auto c = link.receive(5s);
          if (!c || !c->has_correction() || c->correction().time_ticks() != i) {
            failure = fmt::format("no Correction at round {}", i);
            return;
          }
          std::vector<double> doubled(a);
          for (double& v : doubled) v *= 2.0;
          if (!same_bits(c->correction().accelerations_m_s2(), doubled)) {
            failure = fmt::format("Correction differs at round {}", i);
            return;
          }
        }
        link.bye("done");
      } catch (const std::exception& e) {
        failure = e.what();
      }
    });
  }
  int byes = 0;
  const auto deadline = Clock::now() + 20s;
  while (byes < n && Clock::now() < deadline) {
    auto in = coordinator.poll(20ms);
    coordinator.check_alive();
    if (!in) continue;
    const auto& e = in->envelope;
    wire::Envelope reply;
    if (e.has_registration()) {
      reply.mutable_setup()->add_summed_masses_kg(
          0.5 + static_cast<double>(e.registration().node_ids(0)));
    } else if (e.has_free_state()) {
      reply.mutable_correction()->set_time_ticks(e.free_state().time_ticks());
      for (double v : e.free_state().accelerations_m_s2()) {
        reply.mutable_correction()->add_accelerations_m_s2(v * 2.0);
      }
    } else if (e.has_bye()) {
      ++byes;
      continue;
    } else {
      ADD_FAILURE() << "unexpected " << e.ShortDebugString() << " from " << in->domain;
      continue;
    }
    coordinator.send(in->domain, reply);
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(byes, n);
  for (int k = 0; k < n; ++k) EXPECT_EQ(failures[static_cast<std::size_t>(k)], "") << names[k];
  EXPECT_TRUE(coordinator.take_notices().empty());
}

TEST_P(Session, TwoDaemonsInThreads) {
  run_daemons(GetParam(), 2);
}
TEST_P(Session, ThreeDaemonsInThreads) {
  run_daemons(GetParam(), 3);
}

TEST_P(Session, VersionMismatchIsRefusedWithBothValues) {
  auto hello = daemon_hello("car", kHash);
  const std::uint32_t theirs = wire::kProtocolVersion + 41;
  hello.set_protocol_version(theirs);
  const RemoteError e = refusal(*coordinator, hello);
  EXPECT_EQ(e.code(), wire::ERROR_CODE_VERSION_MISMATCH);
  const std::string what = e.what();
  EXPECT_TRUE(has(what, fmt::format("speaks wire protocol version {}", theirs))) << what;
  EXPECT_TRUE(has(what, fmt::format("coordinator speaks version {}", wire::kProtocolVersion)))
      << what;
  EXPECT_TRUE(has(what, "fix:")) << what;
  EXPECT_TRUE(has(what, "'car'")) << what;
  EXPECT_FALSE(coordinator->joined("car"));
  const auto notices = coordinator->take_notices();
  ASSERT_EQ(notices.size(), 1u);
  // The peer is named by its connection: the domain and the session's random part.
  EXPECT_EQ(notices[0].peer.rfind("car#", 0), 0u) << notices[0].peer;
  EXPECT_EQ(notices[0].peer.size(), 4u + 16u) << notices[0].peer;
}

TEST_P(Session, SecondDaemonForAHeldDomainIsRefusedAndTheFirstGoesOn) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  ASSERT_TRUE(coordinator->joined("car"));
  const RemoteError e = refusal(*coordinator, daemon_hello("car", kHash));
  EXPECT_EQ(e.code(), wire::ERROR_CODE_DOMAIN_HELD);
  EXPECT_TRUE(has(e.what(), "domain 'car' is already held")) << e.what();
  EXPECT_TRUE(has(e.what(), "fix:")) << e.what();
  // The first session is untouched: both ways.
  EXPECT_TRUE(coordinator->joined("car"));
  car.send(free_state(1, {1.0}));
  const Incoming in = next_incoming(*coordinator);
  EXPECT_EQ(in.domain, "car");
  EXPECT_TRUE(in.envelope.has_free_state());
  coordinator->send("car", free_state(2, {2.0}));
  const auto back = car.receive(5s);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->free_state().time_ticks(), 2);
}

TEST_P(Session, SealedDomainIsRefusedAfterItsSessionEnded) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  coordinator->seal("car");
  car.bye("done");
  while (coordinator->joined("car")) (void)coordinator->poll(10ms);
  const RemoteError e = refusal(*coordinator, daemon_hello("car", kHash));
  EXPECT_EQ(e.code(), wire::ERROR_CODE_DOMAIN_HELD);
  EXPECT_TRUE(has(e.what(), "has already run")) << e.what();
}

TEST_P(Session, DroppedDomainCanJoinAgain) {
  DaemonLink first = connect_daemon(*coordinator, daemon_hello("wiper", kHash));
  coordinator->drop("wiper", wire::ERROR_CODE_TIMEOUT, "domain 'wiper' dropped for the test");
  EXPECT_FALSE(coordinator->joined("wiper"));
  EXPECT_EQ(coordinator->missing(), (std::vector<std::string>{"car", "wiper", "head"}));
  EXPECT_THROW(
      {
        while (first.receive(5s)) {
        }
      },
      RemoteError);
  DaemonLink second = connect_daemon(*coordinator, daemon_hello("wiper", kHash));
  EXPECT_TRUE(coordinator->joined("wiper"));
}

TEST_P(Session, ScenarioMismatchIsRefusedWithBothValues) {
  const RemoteError e = refusal(*coordinator, daemon_hello("wiper", "deadbeef"));
  EXPECT_EQ(e.code(), wire::ERROR_CODE_SCENARIO_MISMATCH);
  const std::string what = e.what();
  EXPECT_TRUE(has(what, "'deadbeef'")) << what;
  EXPECT_TRUE(has(what, fmt::format("'{}'", kHash))) << what;
  EXPECT_TRUE(has(what, "same scenario file")) << what;
  EXPECT_FALSE(coordinator->joined("wiper"));
}

TEST_P(Session, UnknownDomainIsRefused) {
  const RemoteError e = refusal(*coordinator, daemon_hello("bogus", kHash));
  EXPECT_EQ(e.code(), wire::ERROR_CODE_MODEL);
  EXPECT_TRUE(has(e.what(), "unknown domain 'bogus'")) << e.what();
  EXPECT_TRUE(has(e.what(), "'car', 'wiper', 'head'")) << e.what();
}

/// Writes random bytes to the coordinator's TCP port from a plain socket (no ZeroMQ at all).
void raw_tcp_garbage(const std::string& endpoint) {
  const auto colon = endpoint.rfind(':');
  const int port = std::stoi(endpoint.substr(colon + 1));
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only
  ASSERT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  std::mt19937 rng(7);
  std::string bytes(4096, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  EXPECT_EQ(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(bytes.size()));
  ::close(fd);
}

TEST_P(Session, GarbageIsRejectedAndTheLegitimatePeerStillServed) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  if (GetParam() == Scheme::tcp) raw_tcp_garbage(coordinator->endpoint());
  Dealer intruder(coordinator->endpoint(), "intruder");
  std::mt19937 rng(42);
  std::string random(1000, '\0');
  for (char& c : random) c = static_cast<char>(rng() & 0xff);
  intruder.send_raw(random);
  intruder.send_raw("");
  intruder.send(free_state(0, {1.0}));  // well-formed, but before any Hello
  // The intruder is answered with Errors, one per message.
  for (int i = 0; i < 3; ++i) {
    auto r = intruder.receive(0ms);
    const auto deadline = Clock::now() + 5s;
    while (!r && Clock::now() < deadline) {
      EXPECT_FALSE(coordinator->poll(5ms).has_value());
      r = intruder.receive(0ms);
    }
    ASSERT_TRUE(r && r->ok() && r->envelope.has_error()) << i;
    EXPECT_EQ(r->envelope.error().code(), wire::ERROR_CODE_PROTOCOL);
    EXPECT_TRUE(has(r->envelope.error().message(), "'intruder'"));
  }
  // The legitimate daemon is still served, round after round.
  for (int i = 0; i < 20; ++i) {
    car.send(free_state(i, {2.0}));
    const Incoming in = next_incoming(*coordinator);
    ASSERT_EQ(in.domain, "car");
    ASSERT_TRUE(in.envelope.has_free_state());
    wire::Envelope c;
    c.mutable_correction()->set_time_ticks(i);
    coordinator->send("car", c);
    const auto got = car.receive(5s);
    ASSERT_TRUE(got && got->has_correction());
  }
  const auto notices = coordinator->take_notices();
  int about_intruder = 0;
  for (const auto& n : notices) about_intruder += n.peer == "intruder" && has(n.text, "intruder");
  EXPECT_EQ(about_intruder, 3);
  EXPECT_TRUE(coordinator->dead_peers().empty());
}

TEST_P(Session, SilentDaemonIsDetectedWithinTheTimeoutAndNamed) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  DaemonLink wiper = connect_daemon(*coordinator, daemon_hello("wiper", kHash));
  const auto t0 = Clock::now();  // car has been silent since at most now
  std::vector<std::string> dead;
  while (dead.empty() && Clock::now() < t0 + 3s) {
    EXPECT_FALSE(coordinator->poll(10ms).has_value());
    EXPECT_FALSE(wiper.receive(0ms).has_value());  // wiper keeps heartbeating; car says nothing
    dead = coordinator->dead_peers();
  }
  const auto waited = Clock::now() - t0;
  EXPECT_EQ(dead, std::vector<std::string>{"car"});
  EXPECT_LT(waited, fast_options().peer_timeout + 500ms);
  try {
    coordinator->check_alive();
    FAIL() << "no PeerTimeoutError";
  } catch (const PeerTimeoutError& e) {
    EXPECT_EQ(e.peer(), "car");
    EXPECT_GE(e.silent_for(), fast_options().peer_timeout);
    EXPECT_TRUE(has(e.what(), "domain 'car' silent for")) << e.what();
    EXPECT_TRUE(has(e.what(), coordinator->endpoint())) << e.what();
  }
}

// A daemon at its end time writes its results before its Bye (coordinator_run.cpp): the silence
// allowed to it is longer, and a daemon that dies then is still named once it has passed.
TEST_P(Session, AllowedSilenceDelaysTheTimeoutAndStillEndsIt) {
  const auto t0 = Clock::now();  // car's last message (its handshake) comes after this
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  const auto allowed = 3 * fast_options().peer_timeout;
  coordinator->allow_silence("car", allowed);
  std::vector<std::string> dead;
  while (dead.empty() && Clock::now() < t0 + allowed + 3s) {
    EXPECT_FALSE(coordinator->poll(10ms).has_value());
    dead = coordinator->dead_peers();
  }
  const auto waited = Clock::now() - t0;
  EXPECT_EQ(dead, std::vector<std::string>{"car"});
  EXPECT_GE(waited, allowed);
  try {
    coordinator->check_alive();
    FAIL() << "no PeerTimeoutError";
  } catch (const PeerTimeoutError& e) {
    EXPECT_EQ(e.peer(), "car");
    EXPECT_GE(e.silent_for(), allowed);
    EXPECT_TRUE(has(e.what(), "(peer timeout 1.200 s)")) << e.what();  // 3 x 400 ms
  }
}

TEST_P(Session, CoordinatorGoneIsDetectedByTheDaemonWithinTheTimeout) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  const std::string endpoint = coordinator->endpoint();
  coordinator.reset();
  const auto t0 = Clock::now();
  try {
    while (Clock::now() < t0 + 3s) EXPECT_FALSE(car.receive(1s).has_value());
    FAIL() << "the daemon did not notice within 3 s";
  } catch (const PeerTimeoutError& e) {
    EXPECT_LT(Clock::now() - t0, fast_options().peer_timeout + 500ms);
    EXPECT_EQ(e.endpoint(), endpoint);
    EXPECT_TRUE(has(e.what(), "the coordinator at " + endpoint)) << e.what();
    EXPECT_TRUE(has(e.what(), "domain 'car'")) << e.what();
  }
}

TEST_P(Session, HeartbeatsKeepAnIdleSessionAlive) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  const auto end = Clock::now() + 3 * fast_options().peer_timeout;
  while (Clock::now() < end) {
    EXPECT_FALSE(coordinator->poll(10ms).has_value());
    EXPECT_FALSE(car.receive(10ms).has_value());
    ASSERT_NO_THROW(coordinator->check_alive());
  }
  EXPECT_TRUE(coordinator->take_notices().empty());
}

// A process that was not scheduled for longer than the peer timeout (a loaded machine) finds its
// peer's heartbeats queued in the socket: it reads them before calling the peer dead. Before, the
// coordinator (check_alive) and the daemon (keep_alive, receive) judged by the last message they
// had read, and a run on a machine kept busy by a CPU hog was stopped with "silent for 1.025 s"
// although every process was alive (Sessions.SecondDaemonForARunningDomain... under load).
TEST_P(Session, APeerWhoseHeartbeatsWaitUnreadIsNotCalledDead) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  wire::Envelope beat;
  beat.mutable_heartbeat();
  {
    // the coordinator reads nothing for twice the peer timeout while car keeps sending
    std::atomic<bool> done{false};
    std::thread sender([&] {
      while (!done.load()) {
        car.send(beat);
        std::this_thread::sleep_for(fast_options().heartbeat_interval);
      }
    });
    std::this_thread::sleep_for(2 * fast_options().peer_timeout);
    EXPECT_NO_THROW(coordinator->check_alive());
    done = true;
    sender.join();
  }
  {
    // car reads nothing for twice the peer timeout while the coordinator keeps sending
    std::atomic<bool> done{false};
    std::thread polling([&] {
      while (!done.load()) (void)coordinator->poll(10ms);
    });
    std::this_thread::sleep_for(2 * fast_options().peer_timeout);
    EXPECT_NO_THROW(car.keep_alive());
    EXPECT_NO_THROW((void)car.receive(0ms));
    done = true;
    polling.join();
  }
}

TEST_P(Session, TimeoutsAreHonoured) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  for (auto timeout : {0ms, 120ms}) {
    auto t0 = Clock::now();
    EXPECT_FALSE(coordinator->poll(timeout).has_value());
    EXPECT_GE(Clock::now() - t0, timeout);
    EXPECT_LT(Clock::now() - t0, timeout + 500ms);
    t0 = Clock::now();
    EXPECT_FALSE(car.receive(timeout).has_value());
    EXPECT_GE(Clock::now() - t0, timeout);
    EXPECT_LT(Clock::now() - t0, timeout + 500ms);
  }
}

TEST_P(Session, ErrorsPropagateWithTheDomainName) {
  DaemonLink car = connect_daemon(*coordinator, daemon_hello("car", kHash));
  DaemonLink wiper = connect_daemon(*coordinator, daemon_hello("wiper", kHash));
  DaemonLink head = connect_daemon(*coordinator, daemon_hello("head", kHash));
  EXPECT_TRUE(coordinator->all_joined());

  // A daemon's error, reported by the coordinator with the domain's name.
  wire::Envelope e;
  e.mutable_error()->set_code(wire::ERROR_CODE_NUMERICAL);
  e.mutable_error()->set_message("NaN in node 12 at cycle 40");
  car.send(e);  // no domain filled in: the coordinator adds it
  EXPECT_FALSE(car.open());
  const Incoming in = next_incoming(*coordinator);
  ASSERT_TRUE(in.envelope.has_error());
  EXPECT_EQ(in.domain, "car");
  const RemoteError reported(in.envelope.error());
  EXPECT_EQ(reported.domain(), "car");
  EXPECT_TRUE(has(reported.what(), "domain 'car'")) << reported.what();
  EXPECT_TRUE(has(reported.what(), "NaN in node 12 at cycle 40")) << reported.what();
  EXPECT_FALSE(coordinator->joined("car"));

  // The coordinator's error, thrown in the daemon.
  coordinator->send("wiper", make_error(wire::ERROR_CODE_TIMEOUT, "domain 'car' failed", "car"));
  try {
    (void)wiper.receive(5s);
    FAIL() << "no RemoteError";
  } catch (const RemoteError& x) {
    EXPECT_EQ(x.code(), wire::ERROR_CODE_TIMEOUT);
    EXPECT_TRUE(has(x.what(), "domain 'car' failed")) << x.what();
  }
  EXPECT_FALSE(wiper.open());

  // A clean end from the coordinator.
  coordinator->send("head", make_bye("run finished"));
  const auto bye = head.receive(5s);
  ASSERT_TRUE(bye && bye->has_bye());
  EXPECT_FALSE(head.open());
  EXPECT_THROW((void)head.receive(0ms), ProtocolError);
  EXPECT_TRUE(coordinator->dead_peers().empty());  // ended sessions are not "dead"
}

TEST_P(Session, AwaitAllJoinedKeepsEarlyMessagesAndNamesTheMissing) {
  auto cfg = config({"car", "wiper"});
  cfg.options = fast_options();
  CoordinatorLink link(local_endpoint(GetParam(), "await"), cfg);
  DaemonLink car = connect_daemon(link, daemon_hello("car", kHash));
  try {
    link.await_all_joined(100ms);
    FAIL() << "wiper never joined";
  } catch (const TransportError& e) {
    EXPECT_TRUE(has(e.what(), "domains 'wiper' did not join")) << e.what();
  }
  car.send(free_state(0, {1.0}));
  auto wiper = std::async(std::launch::async, [&] {
    return DaemonLink(link.endpoint(), daemon_hello("wiper", kHash), fast_options());
  });
  link.await_all_joined(5s);
  wiper.get();
  const Incoming early = next_incoming(link);  // car's message, kept during the wait
  EXPECT_EQ(early.domain, "car");
  EXPECT_TRUE(early.envelope.has_free_state());
}

INSTANTIATE_TEST_SUITE_P(AllTransports, Session, kAllSchemes, scheme_test_name);

TEST(CheckHello, AcceptsAMatchingDaemonAndChecksInOrder) {
  const std::vector<std::string> domains = {"car", "wiper"};
  EXPECT_FALSE(check_hello(daemon_hello("car", "h"), "h", domains).has_value());
  auto coordinator_role = daemon_hello("car", "h");
  coordinator_role.set_role(wire::PEER_ROLE_COORDINATOR);
  EXPECT_EQ(check_hello(coordinator_role, "h", domains)->code(), wire::ERROR_CODE_PROTOCOL);
  auto both_wrong = daemon_hello("car", "x");
  both_wrong.set_protocol_version(0);
  EXPECT_EQ(check_hello(both_wrong, "h", domains)->code(),
            wire::ERROR_CODE_VERSION_MISMATCH);  // the version first: the rest may mean nothing
}

TEST(CheckHello, ThePeersStringsAreEscapedInTheRefusal) {
  const std::vector<std::string> domains = {"car"};
  const auto r =
      check_hello(daemon_hello("x\ndone: all domains finished\x1b[2J", "h"), "h", domains);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->message().find('\n'), std::string::npos) << r->message();
  EXPECT_EQ(r->message().find('\x1b'), std::string::npos) << r->message();
  EXPECT_TRUE(has(r->message(), "unknown domain 'x\\x0adone: all domains finished\\x1b[2J'"))
      << r->message();
  EXPECT_EQ(r->domain(), "x\\x0adone: all domains finished\\x1b[2J");
}

TEST(SessionOptionsCheck, IntervalMustBeShorterThanTimeout) {
  SessionOptions o;
  o.heartbeat_interval = 500ms;
  o.peer_timeout = 500ms;
  EXPECT_THROW(o.validate("inproc://x"), TransportError);
  EXPECT_THROW(CoordinatorLink(local_endpoint(Scheme::inproc), CoordinatorConfig{"h", {"a"}, 1, o}),
               TransportError);
}

}  // namespace
}  // namespace crashlink::transport::test
