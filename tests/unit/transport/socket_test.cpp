// Router / Dealer (docs/design.md §3): one Envelope per ZeroMQ message, bit-exact arrays, loud
// sends to unknown peers, bounded receives, garbage reported and never a crash. Every transport.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <random>
#include <string>

#include "transport/dealer.h"
#include "transport/errors.h"
#include "transport/router.h"
#include "transport_test_support.h"

namespace crashlink::transport::test {
namespace {

using Clock = std::chrono::steady_clock;

class Sockets : public ::testing::TestWithParam<Scheme> {
 protected:
  Router router{local_endpoint(GetParam(), "sock")};
};

/// Receives one message within 5 s (fails the test otherwise).
template <class Socket>
Received receive_one(Socket& socket) {
  auto r = socket.receive(5s);
  if (!r) {
    ADD_FAILURE() << "no message within 5 s";
    return {};
  }
  return std::move(*r);
}

TEST_P(Sockets, EphemeralEndpointIsReadBack) {
  const auto& e = router.endpoint();
  const auto parsed = parse_endpoint(e, Use::connect);  // connectable: no '*' left
  EXPECT_EQ(parsed.scheme, GetParam());
  if (GetParam() == Scheme::tcp) {
    EXPECT_TRUE(e.starts_with("tcp://127.0.0.1:")) << e;
  }
}

TEST_P(Sockets, EveryKindRoundTripsBitExactBothWays) {
  Dealer dealer(router.endpoint(), "wiper");
  constexpr std::size_t kNodes = 1000;
  const auto vec = tricky_doubles(3 * kNodes);
  for (const auto& sent : every_kind(kNodes)) {
    SCOPED_TRACE(sent.ShortDebugString().substr(0, 60));
    dealer.send(sent);
    const Received up = receive_one(router);
    ASSERT_TRUE(up.ok()) << up.error;
    EXPECT_EQ(up.peer, "wiper");
    EXPECT_EQ(up.envelope.SerializeAsString(), sent.SerializeAsString());
    router.send("wiper", up.envelope);
    const Received down = receive_one(dealer);
    ASSERT_TRUE(down.ok()) << down.error;
    EXPECT_TRUE(down.peer.empty());
    EXPECT_EQ(down.envelope.SerializeAsString(), sent.SerializeAsString());
    if (down.envelope.has_free_state()) {
      EXPECT_TRUE(same_bits(down.envelope.free_state().accelerations_m_s2(), vec));
      // Packed: 8 bytes per double plus a few bytes of tags and lengths.
      EXPECT_LT(down.envelope.ByteSizeLong(), 2 * 8 * 3 * kNodes + 64);
    }
    if (down.envelope.has_correction()) {
      EXPECT_TRUE(same_bits(down.envelope.correction().accelerations_m_s2(), vec));
    }
    if (down.envelope.has_layer_displacement()) {
      EXPECT_TRUE(same_bits(down.envelope.layer_displacement().displacements_m(), vec));
    }
  }
}

TEST_P(Sockets, SendToUnknownPeerFailsLoudly) {
  wire::Envelope e;
  e.mutable_heartbeat()->set_sequence(1);
  try {
    router.send("nobody", e);
    FAIL() << "send to an unknown peer was accepted";
  } catch (const TransportError& x) {
    EXPECT_EQ(x.endpoint(), router.endpoint());
    EXPECT_NE(std::string(x.what()).find("'nobody'"), std::string::npos) << x.what();
    EXPECT_NE(std::string(x.what()).find("no such peer"), std::string::npos) << x.what();
  }
}

TEST_P(Sockets, ReceiveTimeoutsAreHonoured) {
  Dealer dealer(router.endpoint(), "quiet");
  for (auto timeout : {0ms, 30ms, 150ms}) {
    auto t0 = Clock::now();
    EXPECT_FALSE(router.receive(timeout).has_value());
    auto waited = Clock::now() - t0;
    EXPECT_GE(waited, timeout);
    EXPECT_LT(waited, timeout + 500ms);
    t0 = Clock::now();
    EXPECT_FALSE(dealer.receive(timeout).has_value());
    waited = Clock::now() - t0;
    EXPECT_GE(waited, timeout);
    EXPECT_LT(waited, timeout + 500ms);
  }
}

TEST_P(Sockets, GarbageIsReportedWithThePeerNotACrash) {
  Dealer dealer(router.endpoint(), "intruder");
  dealer.send_raw("\xff\xff\xff\xff\xff");          // a truncated varint
  dealer.send_raw("");                              // parses, but no message in it
  dealer.send_raw(std::string("\x08\x96\x01", 3));  // a varint field 1: not a message body
  for (int i = 0; i < 3; ++i) {
    const Received r = receive_one(router);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.peer, "intruder");
    EXPECT_NE(r.error.find("bytes"), std::string::npos) << r.error;
  }
  // Random bytes of random lengths: each is either an Envelope that happens to parse or an error
  // naming the peer; never a crash (run under ASan/UBSan too).
  std::mt19937 rng(2024);
  for (int i = 0; i < 300; ++i) {
    std::string bytes(rng() % 300, '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    dealer.send_raw(bytes);
    const Received r = receive_one(router);
    EXPECT_EQ(r.peer, "intruder");
    EXPECT_TRUE(r.ok() ? r.envelope.body_case() != wire::Envelope::BODY_NOT_SET
                       : r.error.find("bytes") != std::string::npos);
  }
  // The socket still works.
  dealer.send(every_kind(2)[3]);
  const Received good = receive_one(router);
  EXPECT_TRUE(good.ok()) << good.error;
  EXPECT_TRUE(good.envelope.has_free_state());
}

TEST_P(Sockets, SecondBindOfTheSameEndpointFails) {
  if (GetParam() == Scheme::ipc) GTEST_SKIP() << "ipc rebinds (ZeroMQ replaces the socket file)";
  EXPECT_THROW(Router second(router.endpoint()), TransportError);
}

TEST(SocketsRoutingId, InvalidRoutingIdIsRefused) {
  EXPECT_THROW(Dealer("inproc://x", ""), TransportError);
  EXPECT_THROW(Dealer("inproc://x", std::string(256, 'a')), TransportError);
  EXPECT_THROW(Dealer("inproc://x", std::string("\0a", 2)), TransportError);
}

INSTANTIATE_TEST_SUITE_P(AllTransports, Sockets, kAllSchemes, scheme_test_name);

}  // namespace
}  // namespace crashlink::transport::test
