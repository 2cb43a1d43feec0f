// coupling::LayerRouter (coupling/layer_router.h): routing of the `layer` exchanges, the
// per-interface time order of the vectors and of the fine side's history rows.
#include "coupling/layer_router.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/errors.h"

using namespace crashlink::coupling;
using crashlink::ProtocolError;

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

TEST(LayerRouter, HistoryRowsComeFromTheFineSideInOrder) {
  auto r = two_domains();
  const std::vector<std::int64_t> t{0, 10};
  const std::vector<double> f{1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  const std::vector<double> w{0.0, 0.25};
  const auto rows = r.rows(0, 0, t, f, w);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].time, 10);
  EXPECT_EQ(rows[1].force_N[2], 6.0);
  EXPECT_EQ(rows[1].link_work_J, 0.25);
  const std::vector<std::int64_t> next{20};
  const std::vector<double> f1{0.0, 0.0, 0.0}, w1{0.5};
  EXPECT_THROW(r.rows(1, 0, next, f1, w1), ProtocolError);  // the owner reports no rows
  EXPECT_THROW(r.rows(0, 1, next, f1, w1), ProtocolError);  // no interface 1
  EXPECT_THROW(r.rows(0, 0, next, f, w1), ProtocolError);   // 6 force values for 1 row
  const std::vector<std::int64_t> skip{30};
  try {
    r.rows(0, 0, skip, f1, w1);
    ADD_FAILURE() << "a row at 3H after the one at H was accepted";
  } catch (const ProtocolError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'fine'"), std::string::npos) << what;
    EXPECT_NE(what.find("30 ticks"), std::string::npos) << what;
    EXPECT_NE(what.find("20 ticks"), std::string::npos) << what;
  }
  EXPECT_EQ(r.rows(0, 0, next, f1, w1).size(), 1u);
}

TEST(LayerRouter, ARestartExpectsEverythingOneStepAfterTheCheckpoint) {
  auto r = two_domains();
  r.restore_progress(40, 8);
  EXPECT_EQ(r.forwarded(), 8);
  EXPECT_EQ(r.force(0, 0, 50, vec(1.0), {}).to, 1);
  EXPECT_EQ(r.displacement(1, 0, 50, vec(1.0), {}).to, 0);
  const std::vector<std::int64_t> t{50};
  const std::vector<double> f{0.0, 0.0, 0.0}, w{0.0};
  EXPECT_EQ(r.rows(0, 0, t, f, w).size(), 1u);
}

// A checkpoint at T counts the vectors for the instants up to T (g_A(0..T), u_J(H..T)), not
// those a partner sent ahead (u_J(T + H)): they are routed again after the restart.
TEST(LayerRouter, MessagesThroughAnInstantAreTheForcesFromZeroAndTheDisplacementsFromH) {
  auto r = two_domains();  // H = 10
  EXPECT_EQ(r.messages_through(0), 1);
  EXPECT_EQ(r.messages_through(40), 9);
  for (Tick t = 0; t <= 40; t += 10) {
    r.force(0, 0, t, vec(1.0), {});
    r.displacement(1, 0, t + 10, vec(1.0), {});  // u_J(T + H) sent before g_A(T + H)
  }
  EXPECT_EQ(r.forwarded(), 10);  // ... including u_J(50)
  EXPECT_EQ(std::min(r.forwarded(), r.messages_through(40)), 9);
  LayerRouter two({{0, 1, 2, 10, 1.0}, {2, 1, 1, 30, 1.0}}, {"fine", "coarse", "finer"});
  EXPECT_EQ(two.messages_through(60), (2 * 6 + 1) + (2 * 2 + 1));
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

// Variable steps (set_variable_steps): the instants are whatever the domains choose, so only the
// time order is checked: any later instant goes, an earlier or repeated one is refused, naming
// the domain and both instants; the rows likewise.
TEST(LayerRouter, WithVariableStepsAnyLaterInstantGoesAndAnEarlierOneIsRefused) {
  auto r = two_domains();
  r.set_variable_steps(true);
  EXPECT_EQ(r.force(0, 0, 0, vec(1.0), {}).to, 1);
  EXPECT_EQ(r.displacement(1, 0, 7, vec(0.5), {}).to, 0);  // H = 7, not the planned 10
  EXPECT_EQ(r.force(0, 0, 7, vec(1.0), {}).to, 1);
  EXPECT_EQ(r.displacement(1, 0, 19, vec(0.5), {}).to, 0);      // then 12
  EXPECT_THROW(r.force(0, 0, 7, vec(1.0), {}), ProtocolError);  // repeated
  try {
    r.displacement(1, 0, 15, vec(0.5), {});
    ADD_FAILURE() << "u_J at 15 ticks after the one at 19 was accepted";
  } catch (const ProtocolError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'coarse'"), std::string::npos) << what;
    EXPECT_NE(what.find("15 ticks"), std::string::npos) << what;
    EXPECT_NE(what.find("20 ticks"), std::string::npos) << what;
  }
  const std::vector<double> f{1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, w{0.0, 0.25};
  EXPECT_EQ(r.rows(0, 0, std::vector<std::int64_t>{0, 7}, f, w).size(), 2u);
  EXPECT_THROW(r.rows(0, 0, std::vector<std::int64_t>{5, 19}, f, w), ProtocolError);
}

// Variable steps: a checkpoint at T counts the vectors forwarded for the instants up to T, any
// instants; after a restart every interface expects instants after T, and the count goes on.
TEST(LayerRouter, WithVariableStepsMessagesThroughCountsWhatWasForwardedUpToAnInstant) {
  auto r = two_domains();
  r.set_variable_steps(true);
  Tick t = 0;
  for (int k = 0; k < 100; ++k) {  // steps of 7, 8, 9, 7, ...: no multiple of anything
    r.force(0, 0, t, vec(1.0), {});
    const Tick next = t + 7 + k % 3;
    r.displacement(1, 0, next, vec(1.0), {});  // u_J(T + H) before g_A(T + H)
    t = next;
  }
  // forces at the 100 instants before t and displacements at the 100 after 0, up to t
  EXPECT_EQ(r.forwarded(), 200);
  EXPECT_EQ(r.messages_through(t), 200);
  EXPECT_EQ(r.messages_through(t - 1), 199);                    // not the u_J(t) sent ahead
  EXPECT_THROW((void)r.messages_through(5), std::logic_error);  // folded out of the window
  r.restore_progress(t, 199);
  EXPECT_EQ(r.forwarded(), 199);
  EXPECT_THROW(r.force(0, 0, t, vec(1.0), {}), ProtocolError);  // g_A(t) was used before
  EXPECT_EQ(r.force(0, 0, t + 1, vec(1.0), {}).to, 1);
  EXPECT_EQ(r.messages_through(t + 1), 200);
  const std::vector<double> f{0.0, 0.0, 0.0}, w{0.0};
  EXPECT_THROW(r.rows(0, 0, std::vector<std::int64_t>{t}, f, w), ProtocolError);
  EXPECT_EQ(r.rows(0, 0, std::vector<std::int64_t>{t + 3}, f, w).size(), 1u);
}
