// coupling::leader_step, the variable `layer` leader's choice of H (coupling/step_policy.h): the
// cost model picks the own proposal or a multiple of a holder's, hysteresis keeps the last kind
// of step, the ramp raises by at most 2 % per step and lowers at once, rises under 0.1 % are held,
// the safety scales the own proposal, a domain without a limit takes its holders'.
#include "coupling/step_policy.h"

#include <gtest/gtest.h>

#include <utility>
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

// The step hold (integration::kStepHold = 0.1 %): a proposal that jitters above the last step by
// less than that keeps it (a multi leader's step must not follow the vibration, docs/elements.md
// "Step hold"); a rise of 0.1 % or more is taken, a fall at once.
TEST(StepPolicy, RisesUnderATenthOfAPercentKeepTheLastStep) {
  EXPECT_EQ(step(100099, {}, 100000), 100000);  // +0.099 %: held
  EXPECT_EQ(step(100100, {}, 100000), 100100);  // +0.1 %: taken
  EXPECT_EQ(step(99999, {}, 100000), 99999);    // down: at once
  EXPECT_EQ(step(100099, {}, 0), 100099);       // the first step: no hold
  // a multiple of a holder's jittering proposal alike: 3 x 33 366 = 100 098
  EXPECT_EQ(step(100099, {{33366, 1e6}}, 100000), 100000);
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

// lts with variable steps plans its first owner step from what the leader's rule sees at t = 0
// (coupling::lts_variable_first_proposals): the session-29 bar (coarse 21 hexes, own 2867 ticks;
// fine 9, 1315 without the safety) takes 2 substeps at 2630, where the ceil rule took 3 at 2867.
TEST(LtsVariableFirstProposals, TheLeaderTakesTheRulesFirstChoiceAndFollowersTheirRawProposals) {
  using crashlink::coupling::lts_variable_first_proposals;
  const std::vector<std::pair<int, int>> bar{{0, 1}};  // (coarse, fine)
  const auto p =
      lts_variable_first_proposals({2867, 1183}, {3186, 1315}, bar, {21, 9}, {"coarse", "fine"});
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], 2630);  // 2 x 1315: (21 + 2 x 9) / 2630 below (21 + 3 x 9) / 2867
  EXPECT_EQ(p[1], 1315);
  EXPECT_EQ(p[0], step(2867, {{1315, 9}}, 0, 21));
  // a chain coarse | mid | fine: the leader sees mid's own proposal (its Fbar carries no other);
  // mid and fine keep their own raw ones
  const std::vector<std::pair<int, int>> chain{{0, 1}, {1, 2}};
  const auto c = lts_variable_first_proposals({1000, 450, 200}, {1100, 500, 220}, chain,
                                              {10, 1000, 10}, {"coarse", "mid", "fine"});
  EXPECT_EQ(c[0], step(1000, {{500, 1000}}, 0, 10));
  EXPECT_EQ(c[0], 1000);  // not 880, which the fine's 220 would have made it
  EXPECT_EQ(c[1], 500);
  EXPECT_EQ(c[2], 220);
  // a fine side as fast as its coarse side: capped at its owner's step, not taken as the base
  // (which would halve the owner's first step and then let it jump back)
  const auto even = lts_variable_first_proposals({90000, 90000}, {100000, 100000}, bar, {10, 10},
                                                 {"coarse", "fine"});
  EXPECT_EQ(even[0], 90000);
  EXPECT_EQ(even[1], 90000);
  // two interfaces to one partner count it once, as LayerStepper::choose_step does
  const auto twice = lts_variable_first_proposals({2867, 1183}, {3186, 1315}, {{0, 1}, {0, 1}},
                                                  {21, 9}, {"coarse", "fine"});
  EXPECT_EQ(twice[0], 2630);
}
