// The global stable step (Controls::global_stable_step, integration/global_step.h) on the
// patches of the stable-step survey (studies/stable_step_survey.h): quads and hexahedra at aspect
// ratios 1 to 5 and distortions 0 to 0.4, free and clamped. On each the solver's step must lie in
// [0.9, 1.0] of the patch's own critical step 2/omega_max (eigenvalues of M^-1 K assembled
// column by column from the kernels), and a free vibration at dt_scale 1.0 must stay bounded for
// 1e5 steps.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "studies/stable_step_survey.h"

using namespace crashlink;
using studies::PatchKind;
using studies::PatchShape;

namespace {

std::vector<PatchShape> shapes() {
  std::vector<PatchShape> out;
  for (const auto kind : {PatchKind::Quad, PatchKind::Hex})
    for (const double aspect : {1.0, 2.0, 3.0, 5.0})
      for (const double distort : {0.0, 0.2, 0.4})
        for (const bool clamped : {false, true})
          out.push_back(
              {.kind = kind, .n = 5, .aspect = aspect, .distort = distort, .clamped = clamped});
  return out;
}

std::string name(const testing::TestParamInfo<PatchShape>& info) {
  std::string s = studies::describe(info.param);
  for (auto& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class GlobalStableStep : public testing::TestWithParam<PatchShape> {};

}  // namespace

TEST_P(GlobalStableStep, StepIsBetweenNinetyPercentAndAllOfTheMeshCriticalStep) {
  const auto r = studies::survey_patch(GetParam());
  const double ratio = r.dt_global_s / r.dt_patch_s;
  // 1e-6: the patch's K is a finite difference of the kernels, exact to about 1e-9.
  EXPECT_LE(ratio, 1.0 + 1e-6) << studies::describe(GetParam());
  EXPECT_GE(ratio, 0.9) << studies::describe(GetParam());
  // and never below what the elements alone allow
  EXPECT_GE(r.dt_global_s, r.dt_kernel_s * (1.0 - 1e-12)) << studies::describe(GetParam());
}

// Stable means bounded: past 2/omega_max the highest mode grows by a factor of at least
// 1 + sqrt(omega dt - 2) per step, and 1e5 steps multiply any excess far beyond 1 %
// (GlobalStableStepAbove below: stopped within 20 000 steps at 3.5 % over). Below it the
// central-difference energy is conserved up to its modified-energy swings: measured at most
// 1.0005 of the energy after the first cycle on every patch (`bench_stable_step --vibrate
// 100000`, docs/elements.md "Global stable step").
TEST_P(GlobalStableStep, FreeVibrationAtFullStepStaysBoundedFor100000Steps) {
  const auto v = studies::vibrate_patch(GetParam(), 100000);
  ASSERT_TRUE(v.error.empty()) << studies::describe(GetParam()) << ": " << v.error;
  EXPECT_EQ(v.cycles, 100000);
  ASSERT_GT(v.e0_J, 0.0);
  EXPECT_LT(v.e_max_J / v.e0_J, 1.01) << studies::describe(GetParam());
  EXPECT_LT(v.e_end_J / v.e0_J, 1.01) << studies::describe(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Patches, GlobalStableStep, testing::ValuesIn(shapes()), name);

// The bound above can fail: 9 % over the estimate (3.5 % over the patch's 2/omega_max) the same
// vibration grows without bound, and the guard stops it or the energy passes 2x.
TEST(GlobalStableStepAbove, AStepAboveTheCriticalGrowsWithoutBound) {
  const PatchShape s{.kind = PatchKind::Quad, .n = 5, .aspect = 1.0, .distort = 0.2};
  const auto v = studies::vibrate_patch(s, 20000, 1.09);
  EXPECT_TRUE(!v.error.empty() || v.e_max_J > 2.0 * v.e0_J)
      << "E_max/E_1 " << v.e_max_J / v.e0_J << " after " << v.cycles << " cycles";
}
