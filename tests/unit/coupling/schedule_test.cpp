// The scheduling rule of docs/design.md §2.6 and the interpolation data of [10] of Bourel 2005.
// A simulated run drives the Schedule like daemons would: a domain submits its next free state
// only after its answer, at the instant the answer imposed; arrivals are in a deterministic or a
// seeded random order. Checked on every run: no deadlock (when every unfinished domain waits, an
// answer comes), answers in non-decreasing time, brackets equal to the partner's two consecutive
// states around t with the exact weight (t - t0) / (t1 - t0), and every domain reaches the end.
#include "coupling/schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "coupling/interpolation.h"
#include "coupling/ticks.h"

using crashlink::coupling::Answer;
using crashlink::coupling::Schedule;
using crashlink::coupling::StepPolicy;
using crashlink::coupling::Tick;
using crashlink::coupling::TickClock;
using crashlink::coupling::Weight;
using Pairs = std::vector<std::pair<int, int>>;

namespace {

enum class Arrival { in_order, random };

struct RunStats {
  std::int64_t answers = 0;
  std::int64_t interpolated = 0;     // brackets with t0 < t < t1
  std::vector<std::int64_t> states;  // free states per domain
};

// Stable step of domain k at its n-th state: nominal, or nominal minus a pseudo-random jitter of
// up to 3 % (a variable step, [1]-[2], rounded down to ticks already).
Tick step_of(const std::vector<Tick>& nominal, int k, std::int64_t n, bool jitter) {
  if (!jitter) return nominal[k];
  const auto h = static_cast<std::uint64_t>(n * 2654435761 + k * 40503) % 1000;
  return nominal[k] - nominal[k] * static_cast<Tick>(h) * 3 / 100000;
}

// f(t) = 7 + 3 t, exactly in 128-bit integers: [10] must reproduce a linear function exactly,
// f(t0) (den - num) + f(t1) num == f(t) den.
__extension__ typedef __int128 Int128;  // GCC/Clang extension; products reach 1e23
Int128 linear(Tick t) {
  return 7 + 3 * static_cast<Int128>(t);
}

RunStats simulate(const std::vector<Tick>& nominal, const Pairs& pairs, StepPolicy policy, Tick end,
                  Arrival arrival, unsigned seed, bool jitter = false) {
  const int n = static_cast<int>(nominal.size());
  Schedule s(n, pairs, policy, end);
  std::mt19937_64 rng(seed);
  std::vector<std::vector<Tick>> history(n);    // every submitted time, per domain
  std::vector<std::array<Tick, 2>> payload(n);  // what the caller keeps in the slots
  std::vector<bool> computing(n, true), done(n, false);
  std::vector<Tick> next(n, 0);
  RunStats st;
  st.states.assign(n, 0);
  Tick last_answer = 0;

  while (!std::all_of(done.begin(), done.end(), [](bool d) { return d; })) {
    std::vector<int> ready;
    for (int k = 0; k < n; ++k) {
      if (computing[k]) ready.push_back(k);
    }
    // No deadlock: if nobody is computing, the previous pop loop must have answered someone.
    if (ready.empty()) {
      ADD_FAILURE() << "deadlock: every unfinished domain waits and nothing is answerable";
      return st;
    }
    int k = ready.front();
    if (arrival == Arrival::random) {
      k = ready[std::uniform_int_distribution<std::size_t>(0, ready.size() - 1)(rng)];
    } else {  // the domain furthest behind arrives first
      for (int c : ready) {
        if (next[c] < next[k]) k = c;
      }
    }
    const Tick t = next[k];
    const int slot = s.submit(k, t, step_of(nominal, k, st.states[k], jitter));
    payload[k][slot] = t;
    history[k].push_back(t);
    ++st.states[k];
    computing[k] = false;

    while (auto a = s.pop()) {
      ++st.answers;
      const int d = a->domain;
      EXPECT_FALSE(computing[d]) << "answered a domain that was not waiting";
      EXPECT_EQ(a->time, history[d].back());
      EXPECT_EQ(payload[d][a->slot], a->time);
      EXPECT_GE(a->time, last_answer) << "answers out of time order";
      last_answer = a->time;
      EXPECT_EQ(a->partners.size(), s.partners(d).size());
      for (const auto& b : a->partners) {
        const auto& h = history[b.partner];
        // The partner's last state <= t and first state >= t (consecutive states around t).
        const auto hi = std::lower_bound(h.begin(), h.end(), a->time);
        const auto lo = std::upper_bound(h.begin(), h.end(), a->time);
        EXPECT_TRUE(hi != h.end()) << "partner has no state at >= t";
        EXPECT_TRUE(lo != h.begin()) << "partner has no state at <= t";
        if (hi == h.end() || lo == h.begin()) continue;
        EXPECT_EQ(b.t0, *(lo - 1));
        EXPECT_EQ(b.t1, *hi);
        EXPECT_EQ(payload[b.partner][b.lower_slot], b.t0);
        EXPECT_EQ(payload[b.partner][b.upper_slot], b.t1);
        if (b.exact()) {
          EXPECT_EQ(b.t0, a->time);
          EXPECT_EQ(b.weight.num, 0);
          EXPECT_EQ(b.weight.den, 1);
        } else {
          ++st.interpolated;
          EXPECT_LT(b.t0, a->time);
          EXPECT_LT(a->time, b.t1);
          EXPECT_EQ(b.weight.num, a->time - b.t0);  // [10] numerator
          EXPECT_EQ(b.weight.den, b.t1 - b.t0);     // [10] denominator
          EXPECT_TRUE(linear(b.t0) * (b.weight.den - b.weight.num) + linear(b.t1) * b.weight.num ==
                      linear(a->time) * b.weight.den);
        }
      }
      if (a->stop) {
        EXPECT_EQ(a->time, end);
        done[d] = true;
      } else {
        EXPECT_GT(a->imposed_step, 0);
        EXPECT_LE(a->time + a->imposed_step, end);
        if (policy == StepPolicy::own) {
          EXPECT_LE(a->imposed_step, step_of(nominal, d, st.states[d] - 1, jitter));
        }
        computing[d] = true;
        next[d] = a->time + a->imposed_step;
      }
    }
  }
  EXPECT_TRUE(s.all_finished());
  return st;
}

const TickClock kClock;  // 1 fs ticks

std::vector<Tick> steps(std::initializer_list<double> dt_s) {
  std::vector<Tick> t;
  for (double dt : dt_s) t.push_back(kClock.step_to_ticks(dt));
  return t;
}

}  // namespace

// Mono-scale (docs/design.md §2.3): equal steps, every state is answered as soon as the last
// domain's state at that instant arrives, and no bracket interpolates.
TEST(Schedule, EqualStepsAnswerEveryoneAtOnceWithoutInterpolation) {
  const Tick h = kClock.step_to_ticks(1e-6);
  for (StepPolicy policy : {StepPolicy::own, StepPolicy::common}) {
    Schedule s(3, Pairs{{0, 1}, {1, 2}, {0, 2}}, policy, 100 * h);
    for (Tick t = 0; t <= 100 * h; t += h) {
      for (int k : {2, 0, 1}) {
        EXPECT_FALSE(s.pop().has_value()) << "answered before every domain arrived";
        s.submit(k, t, h);
      }
      for (int k = 0; k < 3; ++k) {  // all three now, in domain order
        const auto a = s.pop();
        ASSERT_TRUE(a.has_value());
        EXPECT_EQ(a->domain, k);
        EXPECT_EQ(a->time, t);
        for (const auto& b : a->partners) EXPECT_TRUE(b.exact());
        EXPECT_EQ(a->stop, t == 100 * h);
        EXPECT_EQ(a->imposed_step, a->stop ? 0 : h);
      }
      EXPECT_FALSE(s.pop().has_value());
    }
    EXPECT_TRUE(s.all_finished());
  }
}

// `common` (modes mono, split): the global minimum stable step is imposed on everyone.
TEST(Schedule, CommonPolicyImposesTheGlobalMinimumStep) {
  const auto h = steps({1e-6, 3e-6});
  const RunStats st =
      simulate(h, Pairs{{0, 1}}, StepPolicy::common, 300 * h[0], Arrival::random, 7);
  EXPECT_EQ(st.states[0], 301);
  EXPECT_EQ(st.states[1], 301);
  EXPECT_EQ(st.interpolated, 0);
}

// The step hold (integration::kStepHold = 0.1 %, docs/elements.md "Step hold"): a proposal that
// rises above the step in force by less than that keeps it, a larger rise is taken, a fall at
// once; under `own` per domain, under `common` for the common step.
TEST(Schedule, StepsHoldAgainstRisesUnderATenthOfAPercent) {
  const std::vector<Tick> proposals{100000, 100050, 100099, 100100, 99000, 99050};
  const std::vector<Tick> imposed{100000, 100000, 100000, 100100, 99000, 99000};
  for (const auto policy : {StepPolicy::own, StepPolicy::common}) {
    const int n = policy == StepPolicy::own ? 1 : 2;
    Schedule s(n, n == 2 ? Pairs{{0, 1}} : Pairs{}, policy, 10000000);
    Tick t = 0;
    for (std::size_t i = 0; i < proposals.size(); ++i) {
      s.submit(0, t, proposals[i]);
      if (n == 2) s.submit(1, t, 3 * proposals[i]);  // the common step is domain 0's
      Tick step = -1;
      for (int k = 0; k < n; ++k) {
        const auto a = s.pop();
        ASSERT_TRUE(a.has_value());
        EXPECT_EQ(a->time, t);
        step = a->imposed_step;
        EXPECT_EQ(step, imposed[i]) << "state " << i << ", " << n << " domain(s)";
      }
      t += step;
    }
  }
}

struct RatioCase {
  const char* name;
  std::vector<double> dt_s;
  Pairs pairs;
};

class ScheduleRatios : public ::testing::TestWithParam<RatioCase> {};

TEST_P(ScheduleRatios, NeverDeadlocksAnswersInOrderWithExactWeights) {
  const auto& c = GetParam();
  std::vector<Tick> nominal;
  for (double dt : c.dt_s) nominal.push_back(kClock.step_to_ticks(dt));
  const Tick fine = *std::min_element(nominal.begin(), nominal.end());
  const Tick end = 3000 * fine;  // thousands of fine steps
  for (bool jitter : {false, true}) {
    SCOPED_TRACE(jitter ? "variable steps" : "constant steps");
    const RunStats a =
        simulate(nominal, c.pairs, StepPolicy::own, end, Arrival::in_order, 0, jitter);
    const RunStats b =
        simulate(nominal, c.pairs, StepPolicy::own, end, Arrival::random, 20240611, jitter);
    // The schedule does not depend on arrival order: the same states, the same answers.
    EXPECT_EQ(a.states, b.states);
    EXPECT_EQ(a.answers, b.answers);
    EXPECT_EQ(a.interpolated, b.interpolated);
    if (!jitter) {
      for (std::size_t k = 0; k < nominal.size(); ++k) {  // ceil(end / h) steps + the state at 0
        EXPECT_EQ(a.states[k], (end + nominal[k] - 1) / nominal[k] + 1) << c.name << " " << k;
      }
    }
    EXPECT_GT(a.interpolated, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Steps, ScheduleRatios,
    ::testing::Values(RatioCase{"ratio_1_3", {1e-6, 3e-6}, {{0, 1}}},
                      RatioCase{"ratio_2_5", {2e-6, 5e-6}, {{0, 1}}},
                      RatioCase{"ratio_1_1p5", {2e-6, 3e-6}, {{0, 1}}},
                      RatioCase{"ratio_3_1_reversed", {3e-6, 1e-6}, {{1, 0}}},
                      RatioCase{"chain_3", {1e-6, 2.5e-6, 7e-6}, {{0, 1}, {1, 2}}},
                      RatioCase{"chain_3_fine_middle", {2.5e-6, 1e-6, 7e-6}, {{0, 1}, {1, 2}}},
                      RatioCase{"triangle_3", {1e-6, 2.5e-6, 7e-6}, {{0, 1}, {1, 2}, {0, 2}}},
                      RatioCase{"chain_4", {1.3e-6, 1e-6, 3.7e-6, 2e-6}, {{0, 1}, {1, 2}, {2, 3}}}),
    [](const ::testing::TestParamInfo<RatioCase>& i) { return std::string(i.param.name); });

// Many seeds on the 3-domain chain: random arrival never breaks the rule.
TEST(Schedule, RandomArrivalOrdersOnAChain) {
  const auto h = steps({1e-6, 2.5e-6, 7e-6});
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const RunStats st =
        simulate(h, Pairs{{0, 1}, {1, 2}}, StepPolicy::own, 500 * h[0], Arrival::random, seed);
    EXPECT_EQ(st.states[0], 501);
  }
}

// Ratio 1:3: instants coincide every third fine step; the weights in between are 1/3 and 2/3.
TEST(Schedule, RatioOneToThreeWeights) {
  const Tick h = kClock.step_to_ticks(1e-6);
  Schedule s(2, Pairs{{0, 1}}, StepPolicy::own, 3 * h);
  s.submit(0, 0, h);
  s.submit(1, 0, 3 * h);
  ASSERT_EQ(s.pop()->domain, 0);
  ASSERT_EQ(s.pop()->domain, 1);
  s.submit(0, h, h);
  EXPECT_FALSE(s.pop().has_value());  // the coarse partner's state at 3h is still missing
  s.submit(1, 3 * h, 3 * h);
  auto a = s.pop();
  ASSERT_TRUE(a && a->domain == 0 && a->time == h);
  EXPECT_EQ(a->partners[0].weight.num, h);
  EXPECT_EQ(a->partners[0].weight.den, 3 * h);
  EXPECT_FALSE(s.pop().has_value());  // coarse at 3h waits for the fine state at 3h
  s.submit(0, 2 * h, h);
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 0 && a->time == 2 * h);
  EXPECT_EQ(a->partners[0].weight.num, 2 * h);
  EXPECT_DOUBLE_EQ(a->partners[0].weight.upper_factor(), 2.0 / 3.0);
  s.submit(0, 3 * h, h);
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 0 && a->time == 3 * h && a->stop);
  EXPECT_TRUE(a->partners[0].exact());
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 1 && a->time == 3 * h && a->stop);
  EXPECT_TRUE(a->partners[0].exact());
  EXPECT_TRUE(s.all_finished());
}

// The last step is clipped so both domains land on the end time (2:5 with end 7 steps of 1).
TEST(Schedule, LastStepLandsOnTheEndTime) {
  Schedule s(2, Pairs{{0, 1}}, StepPolicy::own, 7);
  s.submit(0, 0, 2);
  s.submit(1, 0, 5);
  EXPECT_EQ(s.pop()->imposed_step, 2);
  EXPECT_EQ(s.pop()->imposed_step, 5);
  s.submit(1, 5, 5);
  for (Tick t = 2; t <= 4; t += 2) {
    s.submit(0, t, 2);
    EXPECT_EQ(s.pop()->time, t);
  }
  s.submit(0, 6, 2);
  auto a = s.pop();  // domain 1 at 5 comes first
  ASSERT_TRUE(a && a->domain == 1 && a->time == 5);
  EXPECT_EQ(a->imposed_step, 2);      // clipped from 5
  EXPECT_FALSE(s.pop().has_value());  // domain 0 at 6 waits for domain 1's state at 7
  s.submit(1, 7, 5);
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 0 && a->time == 6);
  EXPECT_EQ(a->imposed_step, 1);            // clipped from 2
  EXPECT_EQ(a->partners[0].weight.num, 1);  // between domain 1's states at 5 and 7
  EXPECT_EQ(a->partners[0].weight.den, 2);
  EXPECT_FALSE(s.pop().has_value());  // domain 1 at 7 waits for domain 0 at 7
  s.submit(0, 7, 2);
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 0 && a->time == 7 && a->stop);
  a = s.pop();
  ASSERT_TRUE(a && a->domain == 1 && a->time == 7 && a->stop);
  EXPECT_TRUE(s.all_finished());
}

// Unclipped (`common` only): everyone keeps the common step and stops at the first instant at or
// after the end time, as a single-domain Solver does.
TEST(Schedule, UnclippedCommonRunStopsAtTheFirstInstantPastTheEnd) {
  Schedule s(2, Pairs{{0, 1}}, StepPolicy::common, 7, /*clip_last_step=*/false);
  Tick t = 0;
  for (;;) {
    s.submit(0, t, 3);
    s.submit(1, t, 4);
    const auto a = s.pop();
    const auto b = s.pop();
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->stop, t >= 7);
    EXPECT_EQ(b->stop, t >= 7);
    if (a->stop) break;
    EXPECT_EQ(a->imposed_step, 3);  // never clipped, 6 -> 9 included
    EXPECT_EQ(b->imposed_step, 3);
    t += 3;
  }
  EXPECT_EQ(t, 9);
  EXPECT_TRUE(s.all_finished());
  // Under `own` a domain stopped past the end could leave its partner unanswerable: refused.
  EXPECT_THROW(Schedule(2, Pairs{{0, 1}}, StepPolicy::own, 7, false), crashlink::ModelError);
}

TEST(Schedule, RejectsProtocolViolations) {
  using crashlink::ProtocolError;
  Schedule s(2, Pairs{{0, 1}}, StepPolicy::own, 100);
  EXPECT_THROW(s.submit(2, 0, 1), ProtocolError);  // unknown domain
  EXPECT_THROW(s.submit(0, 5, 1), ProtocolError);  // first state must be at 0
  EXPECT_THROW(s.submit(0, 0, 0), ProtocolError);  // step must be positive
  s.submit(0, 0, 10);
  EXPECT_THROW(s.submit(0, 10, 10), ProtocolError);  // advancing before its answer
  s.submit(1, 0, 30);
  s.pop();
  s.pop();
  EXPECT_THROW(s.submit(0, 20, 10), ProtocolError);  // not the imposed instant (10)
  EXPECT_THROW(Schedule(2, Pairs{{0, 0}}, StepPolicy::own, 1), crashlink::ModelError);
  EXPECT_THROW(Schedule(2, Pairs{{0, 2}}, StepPolicy::own, 1), crashlink::ModelError);
}

// [10]: coinciding instants return the state bit for bit; in between, the weighted sum.
TEST(Interpolation, FollowsEquationTenExactlyAtTheEnds) {
  const std::vector<double> lo{1.0, -2.0, 0.1}, hi{4.0, 2.0, 0.7};
  std::vector<double> out(3);
  crashlink::coupling::interpolate(lo, hi, Weight{0, 1}, out);
  EXPECT_EQ(out, lo);
  crashlink::coupling::interpolate(lo, hi, Weight{3, 3}, out);
  EXPECT_EQ(out, hi);
  crashlink::coupling::interpolate(lo, hi, Weight{1, 3}, out);
  EXPECT_DOUBLE_EQ(out[0], 2.0);
  EXPECT_DOUBLE_EQ(out[1], -2.0 * 2.0 / 3.0 + 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(out[2], 0.3);
  std::vector<double> short_out(2);
  EXPECT_THROW(crashlink::coupling::interpolate(lo, hi, Weight{1, 3}, short_out),
               crashlink::ModelError);
}
