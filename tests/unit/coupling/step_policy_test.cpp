// coupling::leader_step, the variable `layer` leader's choice of H (coupling/step_policy.h): the
// cost model picks the own proposal or a multiple of a holder's, hysteresis keeps the last kind
// of step, the ramp raises by at most 2 % per step and lowers at once, the safety scales the own
// proposal, a domain without a limit takes its holders'.
#include "coupling/step_policy.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/errors.h"

using crashlink::coupling::HolderProposal;
using crashlink::coupling::leader_step;
using crashlink::coupling::Tick;

namespace {

Tick step(Tick own, const std::vector<HolderProposal>& holders, Tick last, double own_cost = 1000,
          double safety = 1.0) {
  return leader_step(own, safety, own_cost, holders, last, "coarse");
}

TEST(StepPolicy, AloneTheLeaderTakesItsOwnProposal) {
  EXPECT_EQ(step(100, {}, 0), 100);
  EXPECT_EQ(step(100, {}, 100), 100);
}

TEST(StepPolicy, TheCostModelPrefersAMultipleOfAnExpensiveHoldersProposal) {
  // own 100, holder 30: candidates 100 (4 holder substeps) and 90 (3).
  // cheap holder (10 elements): (1000 + 40) / 100 = 10.4 < (1000 + 30) / 90 = 11.4 -> 100
  EXPECT_EQ(step(100, {{30, 10.0}}, 0), 100);
  // expensive holder (10 000): (1000 + 40000) / 100 = 410 > (1000 + 30000) / 90 = 344 -> 90
  EXPECT_EQ(step(100, {{30, 10000.0}}, 0), 90);
}

TEST(StepPolicy, HysteresisKeepsTheLastKindOfStepUnlessFivePercentCheaper) {
  // own 100, holder 30 with cost w: rate(100) = (1000 + 4w) / 100, rate(90) = (1000 + 3w) / 90.
  // w = 300: rate(100) = 22, rate(90) = 21.11: 90 is 4.2 % cheaper, not enough to leave 100.
  EXPECT_EQ(step(100, {{30, 300.0}}, 0), 90);     // first step: the cheapest
  EXPECT_EQ(step(100, {{30, 300.0}}, 100), 100);  // after 100: stays
  // w = 1000: rate(100) = 50, rate(90) = 44.4: 12.5 % cheaper -> leaves 100 for 90
  EXPECT_EQ(step(100, {{30, 1000.0}}, 100), 90);
}

TEST(StepPolicy, TheStepRisesByAtMostTwoPercentAndFallsAtOnce) {
  EXPECT_EQ(step(200, {}, 100), 102);  // up: 100 + 2 % of 100
  EXPECT_EQ(step(200, {}, 10), 11);    // at least one tick
  EXPECT_EQ(step(50, {}, 100), 50);    // down: at once
}

TEST(StepPolicy, TheSafetyScalesTheOwnProposal) {
  EXPECT_EQ(step(100, {}, 0, 1000, 0.9), 90);
  EXPECT_EQ(step(1, {}, 0, 1000, 0.5), 1);  // never below one tick
}

TEST(StepPolicy, WithoutALimitTheLeaderTakesItsHoldersAndNeitherIsRefused) {
  EXPECT_EQ(step(0, {{30, 10.0}, {45, 10.0}}, 0), 45);
  EXPECT_THROW(step(0, {{0, 10.0}}, 0), crashlink::ModelError);
  EXPECT_THROW(step(0, {}, 0), crashlink::ModelError);
}

}  // namespace
