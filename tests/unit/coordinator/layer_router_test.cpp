// coordinator::LayerRouter (coordinator/layer_router.h): routing of the `layer` exchanges, the
// per-interface time order, and the link work by the trapezoid rule on the owner's instants.
#include "coordinator/layer_router.h"

#include <gtest/gtest.h>

#include <vector>

#include "coordinator/protocol_error.h"
#include "solver/core/errors.h"

using namespace crashlink::coordinator;

namespace {

// Domain 0 'fine' holds the layer, domain 1 'coarse' owns two J nodes; H = 10 ticks = 1 s.
LayerRouter two_domains() {
  return LayerRouter({{0, 1, 2, 10, 1.0}}, {"fine", "coarse"});
}

std::vector<double> vec(double x0, double x1 = 0.0) {
  return {x0, 0.0, 0.0, x1, 0.0, 0.0};
}

}  // namespace

TEST(LayerRouter, ForcesGoToTheOwnerDisplacementsToTheHolder) {
  auto r = two_domains();
  EXPECT_EQ(r.force(0, 0, 0, vec(1.0), {}).to, 1);
  EXPECT_EQ(r.displacement(1, 0, 10, vec(0.5), {}).to, 0);
  EXPECT_EQ(r.forwarded(), 2);
}

TEST(LayerRouter, LinkWorkIsTheTrapezoidOnTheOwnerInstants) {
  auto r = two_domains();
  // T = 0: g = (2, 0), u = 0 -> a first row, no work yet.
  auto a = r.force(0, 0, 0, vec(2.0), {});
  ASSERT_EQ(a.samples.size(), 1u);
  EXPECT_EQ(a.samples[0].time, 0);
  EXPECT_EQ(a.samples[0].link_work_J, 0.0);
  EXPECT_EQ(a.samples[0].force_N[0], 2.0);
  // u(H) arrives before g(H) (the holder needs it to reach H): no row until both are there.
  EXPECT_TRUE(r.displacement(1, 0, 10, vec(0.1, 0.3), {}).samples.empty());
  auto b = r.force(0, 0, 10, vec(4.0, 1.0), {});
  ASSERT_EQ(b.samples.size(), 1u);
  // 1/2 (2 + 4) 0.1 + 1/2 (0 + 1) 0.3 = 0.45
  EXPECT_DOUBLE_EQ(b.samples[0].link_work_J, 0.45);
  EXPECT_EQ(b.samples[0].force_N[0], 5.0);
}

TEST(LayerRouter, MomentWorkUsesTheRotationIncrementOfTheOwnerStep) {
  auto r = two_domains();
  (void)r.force(0, 0, 0, vec(0.0), vec(1.0));
  (void)r.displacement(1, 0, 10, vec(0.0), vec(0.5));  // omega(H/2) = 0.5 rad/s, H = 1 s
  const auto b = r.force(0, 0, 10, vec(0.0), vec(3.0));
  ASSERT_EQ(b.samples.size(), 1u);
  EXPECT_DOUBLE_EQ(b.samples[0].link_work_J, 0.5 * (1.0 + 3.0) * 0.5);
}

TEST(LayerRouter, RefusesOutOfOrderWrongSideAndWrongSizes) {
  auto r = two_domains();
  EXPECT_THROW(r.force(0, 0, 10, vec(1.0), {}), ProtocolError);         // first force is at 0
  EXPECT_THROW(r.force(1, 0, 0, vec(1.0), {}), ProtocolError);          // the owner sends no force
  EXPECT_THROW(r.displacement(0, 0, 10, vec(1.0), {}), ProtocolError);  // nor the holder u_J
  EXPECT_THROW(r.force(0, 3, 0, vec(1.0), {}), ProtocolError);          // no interface 3
  const std::vector<double> short_vector{1.0, 2.0};                     // 2 values for 2 nodes
  EXPECT_THROW(r.force(0, 0, 0, short_vector, {}), ProtocolError);
  (void)r.force(0, 0, 0, vec(1.0), {});
  EXPECT_THROW(r.force(0, 0, 0, vec(1.0), {}), ProtocolError);  // the same instant twice
  try {
    r.displacement(1, 0, 20, vec(1.0), {});
    ADD_FAILURE() << "a displacement at 2H before the one at H was accepted";
  } catch (const ProtocolError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'coarse'"), std::string::npos) << what;
    EXPECT_NE(what.find("20 ticks"), std::string::npos) << what;
    EXPECT_NE(what.find("10 ticks"), std::string::npos) << what;
  }
}

TEST(LayerRouter, RefusesBadRoutes) {
  EXPECT_THROW(LayerRouter({{0, 0, 1, 10, 1.0}}, {"a", "b"}), crashlink::ModelError);
  EXPECT_THROW(LayerRouter({{0, 2, 1, 10, 1.0}}, {"a", "b"}), crashlink::ModelError);
  EXPECT_THROW(LayerRouter({{0, 1, 1, 0, 0.0}}, {"a", "b"}), crashlink::ModelError);
}

// A coarse step so long that the next instant leaves the tick range (fuzz regression,
// docs/fuzzing.md): refused by name instead of overflowing.
TEST(LayerRouter, RefusesAnInstantWhoseSuccessorLeavesTheTickRange) {
  const Tick H = 5'000'000'000'000'000'000;
  LayerRouter r({{0, 1, 2, H, 5.0e3}}, {"fine", "coarse"});
  EXPECT_EQ(r.force(0, 0, 0, vec(1.0), {}).to, 1);
  EXPECT_THROW(r.displacement(1, 0, H, vec(0.5), {}), ProtocolError);
}
