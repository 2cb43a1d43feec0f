// Integer ticks (docs/design.md §2.6, coupling/ticks.h): exact conversion, rounding down,
// snapping.
#include "coupling/ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/errors.h"

using crashlink::coupling::Tick;
using crashlink::coupling::TickClock;

TEST(Ticks, DecimalStepsAreWholeTicks) {
  const TickClock clock;  // 1 fs
  EXPECT_EQ(clock.ticks_per_second(), 1'000'000'000'000'000);
  EXPECT_EQ(clock.step_to_ticks(1e-6), 1'000'000'000);
  EXPECT_EQ(clock.step_to_ticks(3e-6), 3'000'000'000);
  EXPECT_EQ(clock.step_to_ticks(1.5e-6), 1'500'000'000);
  EXPECT_EQ(clock.step_to_ticks(2.5e-7), 250'000'000);
  EXPECT_EQ(clock.step_to_ticks(7e-9), 7'000'000);
  EXPECT_EQ(clock.to_ticks(0.12), 120'000'000'000'000);
  EXPECT_EQ(clock.to_ticks(0.0), 0);
  // Ratios written in the scenario survive exactly: 1:3, 2:5, 1:1.5.
  EXPECT_EQ(3 * clock.step_to_ticks(1e-6), clock.step_to_ticks(3e-6));
  EXPECT_EQ(5 * clock.step_to_ticks(2e-6), 2 * clock.step_to_ticks(5e-6));
  EXPECT_EQ(3 * clock.step_to_ticks(2e-6), 2 * clock.step_to_ticks(3e-6));
}

TEST(Ticks, RoundsDownSoTheStableStepIsNeverExceeded) {
  const TickClock clock;
  // A computed stable step between two ticks goes down.
  const double dt = 1.23456789012345e-7;
  const Tick n = clock.step_to_ticks(dt);
  EXPECT_EQ(n, 123'456'789);
  EXPECT_LE(clock.to_seconds(n), dt);
  EXPECT_GT(clock.to_seconds(n + 1), dt);
  // Half a tick and 0.999 ticks above a whole number still round down.
  EXPECT_EQ(clock.to_ticks(1e-6 + 0.5e-15), 1'000'000'000);
  EXPECT_EQ(clock.to_ticks(1e-6 + 0.999e-15), 1'000'000'000);
  // Just below a whole number, beyond the snap band, rounds down to the previous one.
  EXPECT_EQ(clock.to_ticks(1e-6 - 0.01e-15), 999'999'999);
  // Over many pseudo-random steps: n ticks <= dt < n + 1 ticks, up to the documented snap band.
  std::uint64_t s = 12345;
  for (int i = 0; i < 100000; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double x = 1e-9 + 1e-5 * static_cast<double>(s >> 11) * 0x1.0p-53;
    const Tick m = clock.step_to_ticks(x);
    const double excess = clock.to_seconds(m) - x;
    EXPECT_LE(excess, TickClock::kSnapUlps * std::numeric_limits<double>::epsilon() * x) << x;
    EXPECT_GT(clock.to_seconds(m + 1), x) << x;
  }
}

TEST(Ticks, SecondsRoundTripIsExact) {
  const TickClock clock;
  for (Tick n : {Tick{0}, Tick{1}, Tick{7}, Tick{999'999'999}, Tick{1'000'000'000},
                 Tick{123'456'789'012'345}, (Tick{1} << 53) - 1}) {
    EXPECT_EQ(clock.to_ticks(clock.to_seconds(n)), n) << n;
  }
  // to_seconds is the correctly rounded quotient: 1e9 ticks is the double 1e-6 itself.
  EXPECT_EQ(clock.to_seconds(1'000'000'000), 1e-6);
  EXPECT_EQ(clock.to_seconds(120'000'000'000'000), 0.12);
}

TEST(Ticks, OtherTickLengths) {
  const TickClock ps(1'000'000'000'000);  // 1 ps
  EXPECT_EQ(ps.step_to_ticks(1e-6), 1'000'000);
  EXPECT_EQ(ps.step_to_ticks(1.0000004e-6), 1'000'000);  // rounds down
  const TickClock binary(std::int64_t{1} << 50);         // binary tick: every dyadic step is exact
  EXPECT_EQ(binary.step_to_ticks(0x1.0p-20), std::int64_t{1} << 30);
}

TEST(Ticks, RejectsBadInputWithTypedErrors) {
  const TickClock clock;
  EXPECT_THROW(clock.to_ticks(-1e-6), crashlink::NumericalError);
  EXPECT_THROW(clock.to_ticks(std::nan("")), crashlink::NumericalError);
  EXPECT_THROW(clock.to_ticks(std::numeric_limits<double>::infinity()), crashlink::NumericalError);
  EXPECT_THROW(clock.to_ticks(1e4), crashlink::ModelError);         // > 2^62 fs
  EXPECT_THROW(clock.step_to_ticks(1e-16), crashlink::ModelError);  // below one tick
  EXPECT_THROW(TickClock(0), crashlink::ModelError);
  EXPECT_THROW(TickClock((std::int64_t{1} << 53) + 1), crashlink::ModelError);
}
