// coupling::LayerWorkMeter (coupling/layer_work.h): the link work of a `layer` interface by
// the trapezoid rule on the owner's instants, and the resultant layer force.
#include "coupling/layer_work.h"

#include <gtest/gtest.h>

#include <vector>

using namespace crashlink::coupling;

namespace {

// Two J nodes, H = 10 ticks = 1 s.
std::vector<double> vec(double x0, double x1 = 0.0) {
  return {x0, 0.0, 0.0, x1, 0.0, 0.0};
}

}  // namespace

TEST(LayerWorkMeter, LinkWorkIsTheTrapezoidOnTheOwnerInstants) {
  LayerWorkMeter m(1.0);
  // T = 0: g = (2, 0), u = 0 -> a first row, no work yet.
  const auto a = m.add(0, vec(2.0), {}, vec(0.0), {});
  EXPECT_EQ(a.time, 0);
  EXPECT_EQ(a.link_work_J, 0.0);
  EXPECT_EQ(a.force_N[0], 2.0);
  const auto b = m.add(10, vec(4.0, 1.0), {}, vec(0.1, 0.3), {});
  // 1/2 (2 + 4) 0.1 + 1/2 (0 + 1) 0.3 = 0.45
  EXPECT_DOUBLE_EQ(b.link_work_J, 0.45);
  EXPECT_EQ(b.force_N[0], 5.0);
  // The work accumulates: + 1/2 (4 + 4) (0.2 - 0.1) + 1/2 (1 + 1) (0.3 - 0.3) = 0.4.
  const auto c = m.add(20, vec(4.0, 1.0), {}, vec(0.2, 0.3), {});
  EXPECT_DOUBLE_EQ(c.link_work_J, 0.85);
}

TEST(LayerWorkMeter, MomentWorkUsesTheRotationIncrementOfTheOwnerStep) {
  LayerWorkMeter m(1.0);
  (void)m.add(0, vec(0.0), vec(1.0), vec(0.0), {});
  // omega(H/2) = 0.5 rad/s, H = 1 s: 1/2 (1 + 3) 0.5
  const auto b = m.add(10, vec(0.0), vec(3.0), vec(0.0), vec(0.5));
  EXPECT_DOUBLE_EQ(b.link_work_J, 0.5 * (1.0 + 3.0) * 0.5);
}

TEST(LayerWorkMeter, ARestoredMeterGoesOnAsTheOneThatWentOn) {
  LayerWorkMeter a(0.5), b(0.5);
  (void)a.add(0, vec(1.0), vec(2.0), vec(0.0), {});
  (void)a.add(10, vec(3.0), vec(1.0), vec(0.2), vec(0.4));
  b.restore(a.state());
  const auto ra = a.add(20, vec(2.0), vec(1.5), vec(0.5), vec(0.1));
  const auto rb = b.add(20, vec(2.0), vec(1.5), vec(0.5), vec(0.1));
  EXPECT_EQ(ra.link_work_J, rb.link_work_J);
  EXPECT_NE(ra.link_work_J, 0.0);
}
