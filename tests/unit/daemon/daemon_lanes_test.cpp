// daemon::DaemonLanes (solver/daemon/daemon_lanes.h) over loopback tcp: two daemons' lanes
// connected from their Setups; a partner's vector arrives, a message for an interface without a
// lane is left to the coordinator, and anything the scheme does not take on a lane (here a Bye)
// is the lane's protocol error, naming the lane and the message.
#include "solver/daemon/daemon_lanes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "coupling/domain_scheme.h"
#include "transport/session.h"

using namespace crashlink;
using namespace std::chrono_literals;

namespace {

/// A scheme that takes only LayerForce on a lane; nothing else of it is used by the lanes.
class ForcesOnly final : public coupling::DomainScheme {
 public:
  void set_ticks_per_second(std::int64_t) override {}
  integration::Solver& solver() override { throw std::logic_error("unused"); }
  const integration::Solver& solver() const override { throw std::logic_error("unused"); }
  coupling::Tick time() const override { return 0; }
  bool uses_lanes() const override { return true; }
  std::vector<coupling::LanePartner> lane_partners() const override { return {}; }
  bool lane_message(const wire::Envelope& e) const override { return e.has_layer_force(); }
  void fill_register(wire::Register&) const override {}
  bool start(const wire::Setup&) override { return false; }
  void initialize() override {}
  coupling::Pace advance(const std::function<void()>&, coupling::Tick) override {
    return coupling::Pace::Finished;
  }
  void drain_outbox(const std::function<void(const coupling::Outgoing&)>&) override {}
  void set_on_outbox(std::function<void()>) override {}
  void deliver(wire::Envelope&&) override {}
  std::optional<wire::Envelope> report(bool) override { return std::nullopt; }
  void fill_bye(wire::DomainReport&) const override {}
  bool at_cycle_boundary() const override { return true; }
  coupling::Tick end_time() const override { return 0; }
  void save_state(core::StateWriter&) const override {}
  void restore_state(const core::StateReader&) override {}
};

wire::Setup lane_to(const std::string& partner, const daemon::DaemonLanes& lanes) {
  wire::Setup s;
  auto* l = s.add_lanes();
  l->set_domain(partner);
  l->set_endpoint(lanes.endpoint());
  l->set_public_key(lanes.public_key());
  return s;
}

/// The next message on `lanes` within 5 s (a busy machine), or nullopt.
std::optional<wire::Envelope> next(daemon::DaemonLanes& lanes, const ForcesOnly& scheme) {
  for (int i = 0; i < 250; ++i)
    if (auto m = lanes.receive(20ms, scheme)) return m;
  return std::nullopt;
}

TEST(DaemonLanes, APartnersVectorPassesAndAnythingElseIsTheLanesProtocolError) {
  const transport::SessionOptions session;
  daemon::DaemonLanes a("a", session), b("b", session);
  a.open_own("tcp://127.0.0.1:5555");  // a loopback session: a tcp lane on an ephemeral port
  b.open_own("tcp://127.0.0.1:5555");
  ASSERT_FALSE(a.endpoint().empty());
  ASSERT_FALSE(b.endpoint().empty());
  a.connect(lane_to("b", b), {{0, "b", 4}}, [] {});
  b.connect(lane_to("a", a), {{0, "a", 4}}, [] {});
  ASSERT_TRUE(a.active());
  const ForcesOnly scheme;

  wire::Envelope force;
  force.mutable_layer_force()->set_interface_index(0);
  ASSERT_TRUE(a.send(0, force));
  const auto got = next(b, scheme);
  ASSERT_TRUE(got.has_value());
  EXPECT_TRUE(got->has_layer_force());
  EXPECT_FALSE(a.send(7, force)) << "no lane for interface 7: the coordinator's to route";

  ASSERT_TRUE(a.send(0, transport::make_bye("not a vector")));
  try {
    (void)next(b, scheme);
    FAIL() << "a Bye on a lane was taken";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.peer(), "lane");
    const std::string what = e.what();
    EXPECT_NE(what.find("domain 'b' got bye on its lane"), std::string::npos) << what;
    EXPECT_NE(what.find("from 'a'"), std::string::npos) << what;
  }
}

}  // namespace
