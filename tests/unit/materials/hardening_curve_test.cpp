#include <gtest/gtest.h>

#include "core/errors.h"
#include "solver/materials/material.h"

using crashlink::materials::HardeningCurve;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

// Exact arithmetic on a piecewise-linear curve: tolerances are round-off (1e-9 relative).
TEST(HardeningCurve, InterpolatesAndExtrapolatesWithLastSlope) {
  HardeningCurve c{{0.0, 0.1, 0.3}, {200e6, 300e6, 340e6}};
  EXPECT_DOUBLE_EQ(c.yield(0.0), 200e6);
  EXPECT_NEAR(c.yield(0.05), 250e6, 1e-3);
  EXPECT_NEAR(c.yield(0.2), 320e6, 1e-3);
  EXPECT_NEAR(c.yield(0.5), 380e6, 1e-3);  // last slope 200 MPa per unit strain
  EXPECT_NEAR(c.slope(0.05), 1e9, 1e-3);
  EXPECT_NEAR(c.slope(0.1), 2e8, 1e-3);  // right-hand slope at the kink
  EXPECT_NEAR(c.slope(1.0), 2e8, 1e-3);
}

TEST(Material, DerivedModuliOfSteel) {
  Material m{"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
  EXPECT_NEAR(m.shear_modulus_Pa(), 210e9 / 2.6, 1.0);
  EXPECT_NEAR(m.bulk_modulus_Pa(), 210e9 / 1.2, 1.0);
  // c = sqrt(E(1-nu)/(rho(1+nu)(1-2nu))) = 6001.6 m/s for steel
  EXPECT_NEAR(m.dilatational_wave_speed_m_s(), std::sqrt(210e9 * 0.7 / (7850.0 * 1.3 * 0.4)), 1e-9);
  EXPECT_NEAR(m.plate_wave_speed_m_s(), std::sqrt(210e9 / (7850.0 * 0.91)), 1e-9);
}

TEST(Material, RejectsNonPhysicalParametersWithTheValue) {
  Material m{"bad", MaterialKind::Elastic, 7850.0, 210e9, 0.5, {}};
  try {
    validate(m);
    FAIL() << "nu = 0.5 accepted";
  } catch (const crashlink::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("Poisson ratio 0.5"), std::string::npos) << e.what();
  }
  Material j{"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.0}, {2e8, 3e8}}};
  EXPECT_THROW(validate(j), crashlink::ModelError);
}
