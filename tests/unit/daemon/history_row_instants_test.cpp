// daemon::HistoryRowInstants: the coarse instants a daemon samples the lts energy at are exactly
// those its history rows read, rows summed as run::DomainRecorder sums them, over long runs (the
// sum's rounding grows with the row count).
#include "solver/daemon/history_row_instants.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <set>

using crashlink::daemon::HistoryRowInstants;

namespace {

/// Every coarse instant up to end_s asked as the stepper asks (t, t + P, t + 2 P), against the
/// set the recorder's rows map to; returns the rows checked.
std::int64_t check(double interval_s, std::int64_t tps, std::int64_t period, double end_s) {
  HistoryRowInstants rows(interval_s, tps, period);
  std::set<std::int64_t> read;  // the recorder: instant = next; next += interval
  std::int64_t count = 0;
  for (double next = 0.0; next <= end_s; next += interval_s, ++count)
    read.insert(rows.coarse_instant(next));
  const auto end = static_cast<std::int64_t>(end_s * static_cast<double>(tps));
  std::int64_t missed = 0, extra = 0;
  for (std::int64_t t = 0; t + 2 * period <= end; t += period) {
    const bool a = rows.reads(t);
    rows.reads(t + period);
    rows.reads(t + 2 * period);
    const bool want = read.count(t) != 0;
    missed += want && !a;
    extra += a && !want;
  }
  EXPECT_EQ(missed, 0) << "interval " << interval_s << " s, period " << period;
  EXPECT_EQ(extra, 0) << "interval " << interval_s << " s, period " << period;
  return count;
}

}  // namespace

// The review's case: rows every 2 us against a 1 us coarse step, to 1 s (an accumulated interval
// that drifted from k interval by the sum's rounding gave NaN rows from 0.55 s with the earlier
// k-interval test); and the head impact's 10 us against 1.4174 us.
TEST(HistoryRowInstants, EveryRowsInstantAndNoOtherOverLongRuns) {
  constexpr std::int64_t tps = 1'000'000'000'000'000;  // 1e15 ticks per second
  const auto rows1 = check(2e-6, tps, 1'000'000'000, 1.0);
  const auto rows2 = check(1e-5, tps, 1'417'400'000, 0.2);
  const auto rows3 = check(2e-7, tps, 100'000'000, 0.05);  // 0.1 us step, 0.2 us rows
  std::printf("[measured] %lld, %lld and %lld rows: each read instant sampled, none other\n",
              static_cast<long long>(rows1), static_cast<long long>(rows2),
              static_cast<long long>(rows3));
}

// A history interval far past any run (1e20 s: rows off but the first) or past the last tick
// (1e4 s at 1e15 ticks per second): instant 0 only, no overflow, no endless loop.
TEST(HistoryRowInstants, HugeIntervalsReadTheFirstInstantOnly) {
  for (const double interval : {1e4, 1e20}) {
    HistoryRowInstants rows(interval, 1'000'000'000'000'000, 1'000'000'000);
    EXPECT_TRUE(rows.reads(0)) << interval;
    for (std::int64_t t = 1'000'000'000; t < 100'000'000'000; t += 1'000'000'000)
      EXPECT_FALSE(rows.reads(t)) << interval << " s at " << t;
  }
}

TEST(HistoryRowInstants, EveryCoarseInstantWhenRowsAreDenser) {
  HistoryRowInstants every(0.0, 1'000'000, 7);
  HistoryRowInstants dense(1e-6, 1'000'000, 3);  // interval 1 tick < period 3 ticks
  for (std::int64_t t = 0; t < 100; t += 7) EXPECT_TRUE(every.reads(t));
  for (std::int64_t t = 0; t < 100; t += 3) EXPECT_TRUE(dense.reads(t));
}
