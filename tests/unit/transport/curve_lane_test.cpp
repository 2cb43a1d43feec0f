// A daemon's CURVE lane (docs/processes.md "Lanes"): a Router bound before the keys it accepts
// are known (CurveOptions::authorize_later); a partner that connects early waits for
// Router::authorize and is then accepted with its key; any other key is refused. Forced CURVE on
// loopback tcp, as the lanes across hosts use it.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "curve_test_support.h"
#include "transport/curve_errors.h"
#include "transport/dealer.h"
#include "transport/router.h"
#include "transport/session.h"

using namespace crashlink;
using namespace crashlink::transport;
using namespace std::chrono_literals;

namespace {

SocketOptions lane_server(const CurveKeyFiles& own) {
  SocketOptions o;
  o.curve.force = true;
  o.curve.secret_key_file = own.secret_file;
  o.curve.authorize_later = true;
  return o;
}

SocketOptions lane_client(const CurveKeyFiles& own, const std::string& server_key) {
  SocketOptions o;
  o.curve.force = true;
  o.curve.secret_key_file = own.secret_file;
  o.curve.server_key = server_key;  // in memory, as the Setup gives it
  return o;
}

wire::Envelope hello() {
  return make_bye("lane test");
}

}  // namespace

TEST(CurveLane, AnEarlyPartnerWaitsForTheKeysThenIsAccepted) {
  test::KeyDir keys;
  const auto coarse = keys.pair("coarse"), fine = keys.pair("fine");
  Router lane("tcp://127.0.0.1:*", lane_server(coarse));
  ASSERT_TRUE(lane.curve());
  EXPECT_EQ(lane.curve_public_key(), coarse.public_key);
  Dealer partner(lane.endpoint(), "fine", lane_client(fine, lane.curve_public_key()));
  partner.send(hello());  // queued: the handshake waits on the ZAP handler for the keys
  EXPECT_FALSE(lane.receive(300ms).has_value()) << "accepted before its key was known";
  lane.authorize({fine.public_key});
  const auto m = lane.receive(5000ms);
  ASSERT_TRUE(m.has_value());
  EXPECT_TRUE(m->ok()) << m->error;
  EXPECT_EQ(m->peer, "fine");
}

TEST(CurveLane, AKeyTheSetupDidNotGiveIsRefused) {
  test::KeyDir keys;
  const auto coarse = keys.pair("coarse"), fine = keys.pair("fine"), other = keys.pair("other");
  Router lane("tcp://127.0.0.1:*", lane_server(coarse));
  lane.authorize({fine.public_key});
  Dealer stranger(lane.endpoint(), "fine", lane_client(other, lane.curve_public_key()));
  stranger.send(hello());
  EXPECT_FALSE(lane.receive(1000ms).has_value());
  const auto refused = lane.take_refusals();
  ASSERT_FALSE(refused.empty());
  EXPECT_NE(refused.front().text.find(other.public_key), std::string::npos) << refused.front().text;
  EXPECT_NE(refused.front().text.find("partners"), std::string::npos) << refused.front().text;
}
