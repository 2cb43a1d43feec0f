// nested_steps (coupling/nested_steps.h): every step a whole number of ticks, no step above its
// proposal, fine sides landing on every coarse instant, the study's 'uniform' substeps.
#include "coupling/nested_steps.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/errors.h"

namespace crashlink::coupling {
namespace {

void expect_nested(const StepPlan& p, const std::vector<Tick>& proposal,
                   const std::vector<std::pair<int, int>>& links) {
  for (std::size_t k = 0; k < proposal.size(); ++k) {
    EXPECT_GT(p.step[k], 0);
    EXPECT_EQ(p.base % p.step[k], 0) << "domain " << k;
    if (proposal[k] > 0) {
      EXPECT_LE(p.step[k], proposal[k]) << "domain " << k;
    }
  }
  for (const auto& [c, f] : links)
    EXPECT_EQ(p.step[static_cast<std::size_t>(c)] % p.step[static_cast<std::size_t>(f)], 0)
        << c << " -> " << f;
}

TEST(NestedSteps, SplitTakesTheGlobalMinimum) {
  const auto p = nested_steps({3000000, 1000000, 0}, {{0, 1}}, true);
  EXPECT_EQ(p.step, (std::vector<Tick>{1000000, 1000000, 1000000}));
}

TEST(NestedSteps, IntegerRatioKeepsBothSteps) {
  const auto p = nested_steps({4000000, 1000000}, {{0, 1}}, false);
  EXPECT_EQ(p.step[0], 4000000);
  EXPECT_EQ(p.step[1], 1000000);
}

TEST(NestedSteps, NonIntegerRatioRunsCeilUniformSubsteps) {
  // r = 1.5: two fine substeps of 0.75 h; r = 4.7: five of 0.94 h.
  auto p = nested_steps({1500000, 1000000}, {{0, 1}}, false);
  EXPECT_EQ(p.n[1], 2);
  EXPECT_EQ(p.step[1], 750000);
  p = nested_steps({4700000, 1000000}, {{0, 1}}, false);
  EXPECT_EQ(p.n[1], 5);
  EXPECT_EQ(p.step[1], 940000);
}

TEST(NestedSteps, ChainAndTwoOwnersNest) {
  // chain 0 -> 1 -> 2 and a domain 3 fine side to both 0 and 1.
  const std::vector<Tick> prop{9000000, 2900000, 700000, 2000000};
  const std::vector<std::pair<int, int>> links{{0, 1}, {1, 2}, {0, 3}, {1, 3}};
  const auto p = nested_steps(prop, links, false);
  expect_nested(p, prop, links);
  EXPECT_EQ(p.n[1], 4);   // 9/2.9 -> 4
  EXPECT_EQ(p.n[3], 8);   // multiple of 4 with 9/8 <= 2
  EXPECT_EQ(p.n[2], 16);  // multiple of 4 with 9/16 <= 0.7
}

TEST(NestedSteps, RigidOnlyDomainFollowsItsPartner) {
  const auto p = nested_steps({0, 1000000}, {{1, 0}}, false);
  EXPECT_EQ(p.step[0], 1000000);
  EXPECT_EQ(p.step[1], 1000000);
}

TEST(NestedSteps, RandomPlansKeepEveryPromise) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<Tick> dt(100000, 100000000);
  for (int trial = 0; trial < 500; ++trial) {
    const std::size_t nd = 2 + trial % 5;
    std::vector<Tick> prop(nd);
    for (auto& x : prop) x = dt(rng);
    std::vector<std::pair<int, int>> links;
    for (std::size_t a = 0; a < nd; ++a)
      for (std::size_t b = a + 1; b < nd; ++b)
        if (rng() % 2) {  // coarse side = the larger proposal, as decompose() picks it
          const bool a_coarse = prop[a] >= prop[b];
          links.emplace_back(static_cast<int>(a_coarse ? a : b),
                             static_cast<int>(a_coarse ? b : a));
        }
    try {
      expect_nested(nested_steps(prop, links, false), prop, links);
    } catch (const ModelError&) {
      // lcm too large for the tick: allowed, never a silent wrong plan
    }
  }
}

TEST(NestedSteps, CycleAndNoLimitAreRefused) {
  EXPECT_THROW(nested_steps({1000, 1000}, {{0, 1}, {1, 0}}, false, {"a", "b"}), ModelError);
  EXPECT_THROW(nested_steps({0, 0}, {}, false), ModelError);
}

}  // namespace
}  // namespace crashlink::coupling

namespace crashlink::coupling {
namespace {
TEST(NestedSteps, RatioJustAboveAWholeNumberShrinksTheBase) {
  // 2 h + 1 tick: two substeps with a coarse step of exactly 2 h, not three
  const auto p = nested_steps({2000001, 1000000}, {{0, 1}}, false);
  EXPECT_EQ(p.n[1], 2);
  EXPECT_EQ(p.step[1], 1000000);
  EXPECT_EQ(p.step[0], 2000000);
  // 2.05 h: a real excess, three substeps
  EXPECT_EQ(nested_steps({2050000, 1000000}, {{0, 1}}, false).n[1], 3);
}
// Proposals near 2^63 ticks (fuzz regression, docs/fuzzing.md): the plan is still exact, and a
// chain whose substep counts leave the tick range is refused by name instead of overflowing.
TEST(NestedSteps, HugeProposalsPlanOrFailWithinTheTickRange) {
  const std::vector<Tick> huge{9'000'000'000'000'000'000, 528'184'804};
  const auto p = nested_steps(huge, {{0, 1}}, false);
  expect_nested(p, huge, {{0, 1}});
  try {
    (void)nested_steps({4'000'000'000'000'000'000, 1, 4'000'000'000'000'000'000}, {{0, 1}, {1, 2}},
                       false);
    ADD_FAILURE() << "no error for substep counts beyond the tick range";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("tick range"), std::string::npos) << e.what();
  }
}
// aligned_end: the end rounded up to the first instant every domain lands on, lcm(steps) =
// base / gcd(n); an end already on it stays; one leaving the tick range is refused.
TEST(NestedSteps, AlignedEndIsTheFirstCommonInstantAtOrAfterTheEnd) {
  StepPlan p;
  p.base = 24;
  p.n = {1, 3};  // steps 24 and 8: common instants every 24
  p.step = {24, 8};
  EXPECT_EQ(aligned_end(p, 10), 24);
  EXPECT_EQ(aligned_end(p, 48), 48);
  EXPECT_EQ(aligned_end(p, 0), 0);
  p.n = {3, 3};  // both at 8 (a fine side with the larger proposal): every 8, not every 24
  p.step = {8, 8};
  EXPECT_EQ(aligned_end(p, 10), 16);
  p.n = {2, 6};  // 12 and 4: every 12
  p.step = {12, 4};
  EXPECT_EQ(aligned_end(p, 13), 24);
  p.base = std::numeric_limits<Tick>::max() / 2;
  p.n = {1};
  p.step = {p.base};
  EXPECT_THROW(aligned_end(p, p.base * 2 - 1 + 2), ModelError);
}

}  // namespace
}  // namespace crashlink::coupling
