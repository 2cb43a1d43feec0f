// The stability map's contact case (studies/contact_drop.h; issue #5 "penalty scale
// factors"): a fine block dropped on a coarse slab across the domains. `layer` stays bounded at
// penalty scales 0.1, 1 and 10 (the penalty enters the stable step, so the planned steps follow
// it); a step planned for a soft penalty is refused by the solver of a stiff one with a message
// naming the contact, never run into NaN.
#include "studies/contact_drop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors.h"
#include "solver/integration/solver.h"

using namespace crashlink;

TEST(ContactDrop, LayerStaysBoundedAtEveryPenaltyScale) {
  for (const double k : {0.1, 1.0, 10.0}) {
    const auto res = studies::run_layer_contact_drop(4.0, k, 20000);
    std::printf(
        "[measured] contact drop, layer, r = %g (nested %g), penalty x%g, 20000 fine steps: max "
        "rise %.3e of E0, E_end/E0 %.4f%s%s\n",
        4.0, res.ratio, k, res.rise, res.e0_J > 0 ? res.e_end_J / res.e0_J : 0.0,
        res.error.empty() ? "" : ", stopped: ", res.error.c_str());
    EXPECT_TRUE(res.error.empty()) << "penalty x" << k << ": " << res.error;
    EXPECT_EQ(res.ratio, 4.0) << "penalty x" << k;
    EXPECT_TRUE(std::isfinite(res.e_end_J));
    // Measured 2.0e-2 (x0.1), 4.2e-3 (x1), 3.7e-4 (x10): the impact's coupling transient.
    EXPECT_LT(res.rise, 0.05) << "penalty x" << k;
    EXPECT_LT(std::abs(res.e_end_J / res.e0_J - 1.0), 0.05) << "penalty x" << k;
  }
}

TEST(ContactDrop, AStepPlannedForASoftPenaltyIsRefusedWithAStiffOne) {
  auto soft = studies::contact_drop_model(4.0, 0.1);
  soft.domains.clear();
  integration::Solver s(soft, "soft");
  s.initialize();
  const double h_soft = s.dt_s();

  auto stiff = studies::contact_drop_model(4.0, 1000.0);
  stiff.domains.clear();
  integration::Solver t(stiff, "stiff");
  t.initialize();
  ASSERT_LT(t.dt_s(), h_soft) << "the stiffer penalty does not shorten the stable step";
  try {
    t.impose_step(h_soft);
    ADD_FAILURE() << "a step of " << h_soft << " s above the stiff contact's " << t.dt_s()
                  << " s was accepted";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("penalty springs of contact 'block_on_slab'"), std::string::npos) << what;
    std::printf("[measured] stiff penalty x1000: stable step %.3e s against %.3e s at x0.1; %s\n",
                t.dt_s(), h_soft, what.c_str());
  }
}
