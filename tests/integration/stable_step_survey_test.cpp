// The stable-step survey (studies/stable_step_survey.h) on small patches: the harness against what
// must hold whatever the estimates: a one-element patch is its own element (the element bound
// equals the patch's 2/omega_max), Irons' theorem (omega_max of an assembly <= the largest element
// omega_max,e, so the element bound never exceeds the patch's step, free or clamped), and the
// kernel's estimate, which runs use, is stable (at most the patch's step).
#include "studies/stable_step_survey.h"

#include <gtest/gtest.h>

#include "core/errors.h"

using namespace crashlink;
using studies::PatchKind;
using studies::PatchShape;

namespace {

PatchShape shape(PatchKind kind, int n, double aspect, double distort, bool clamped) {
  return {.kind = kind, .n = n, .aspect = aspect, .distort = distort, .clamped = clamped};
}

}  // namespace

TEST(StableStepSurvey, OneElementIsItsOwnPatch) {
  for (const auto kind : {PatchKind::Quad, PatchKind::Hex}) {
    const auto s = shape(kind, 1, 2.0, 0.0, false);
    const auto r = studies::survey_patch(s);
    EXPECT_EQ(r.elements, 1) << studies::describe(s);
    EXPECT_NEAR(r.dt_element_s / r.dt_patch_s, 1.0, 1e-9) << studies::describe(s);
  }
}

TEST(StableStepSurvey, ElementBoundAndKernelNeverExceedThePatch) {
  for (const auto& s :
       {shape(PatchKind::Quad, 3, 1.0, 0.3, false), shape(PatchKind::Quad, 3, 3.0, 0.0, true),
        shape(PatchKind::Hex, 2, 1.0, 0.2, false), shape(PatchKind::Hex, 3, 2.0, 0.0, true)}) {
    const auto r = studies::survey_patch(s);
    // 1e-6: the finite-difference stiffness is exact to about 1e-9 relative.
    EXPECT_LE(r.dt_element_s, r.dt_patch_s * (1.0 + 1e-6)) << studies::describe(s);
    EXPECT_LE(r.dt_kernel_s, r.dt_patch_s * (1.0 + 1e-6)) << studies::describe(s);
    EXPECT_GT(r.dt_kernel_s, 0.4 * r.dt_patch_s) << studies::describe(s);
    EXPECT_GT(r.dt_lsdyna_s, 0.0) << studies::describe(s);
  }
}

// The power method's Rayleigh quotient never exceeds omega_max^2, so its step estimate is at or
// above the patch's and falls towards it with the iterations.
TEST(StableStepSurvey, PowerEstimateFallsTowardsThePatchFromAbove) {
  for (const auto& s :
       {shape(PatchKind::Quad, 3, 1.0, 0.3, true), shape(PatchKind::Hex, 2, 2.0, 0.2, false)}) {
    const auto r = studies::survey_patch(s);
    double previous = 1e300;
    for (const double ratio : r.power_ratio) {
      EXPECT_GE(ratio, 1.0 - 1e-9) << studies::describe(s);
      EXPECT_LE(ratio, previous * (1.0 + 1e-12)) << studies::describe(s);
      previous = ratio;
    }
  }
}

TEST(StableStepSurvey, AShapeOutOfRangeIsRefused) {
  EXPECT_THROW(studies::survey_patch(shape(PatchKind::Quad, 3, 1.0, 0.5, false)), ModelError);
  EXPECT_THROW(studies::survey_patch(shape(PatchKind::Hex, 3, 0.5, 0.0, false)), ModelError);
}
