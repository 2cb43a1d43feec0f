// coupling::StallWatch: a run is stuck when no domain's instant and no count of finished
// domains has changed for longer than the limit; any change restarts the count.
#include "coupling/stall_watch.h"

#include <gtest/gtest.h>

using crashlink::coupling::StallWatch;
using namespace std::chrono_literals;

TEST(StallWatch, StuckOnlyAfterTheLimitWithoutAnyMove) {
  StallWatch w(2s);
  const auto t0 = StallWatch::Clock::time_point{} + 100s;
  std::vector<std::int64_t> latest{10, 20, 30};
  EXPECT_FALSE(w.stuck(latest, 0, t0));
  EXPECT_FALSE(w.stuck(latest, 0, t0 + 1s));
  EXPECT_FALSE(w.stuck(latest, 0, t0 + 2s));  // not longer than the limit yet
  EXPECT_TRUE(w.stuck(latest, 0, t0 + 2s + 1ms));
  EXPECT_EQ(w.still_for(), 2s + 1ms);
}

TEST(StallWatch, AnyDomainMovingOrFinishingRestartsTheCount) {
  StallWatch w(2s);
  const auto t0 = StallWatch::Clock::time_point{} + 100s;
  std::vector<std::int64_t> latest{10, 20, 30};
  EXPECT_FALSE(w.stuck(latest, 0, t0));
  latest[2] = 31;  // one domain moved
  EXPECT_FALSE(w.stuck(latest, 0, t0 + 1900ms));
  EXPECT_FALSE(w.stuck(latest, 0, t0 + 3s));      // 1.1 s since the move
  EXPECT_FALSE(w.stuck(latest, 1, t0 + 3900ms));  // one finished
  EXPECT_FALSE(w.stuck(latest, 1, t0 + 5900ms));
  EXPECT_TRUE(w.stuck(latest, 1, t0 + 6s));
}
