// J2 hexahedron under uniaxial stress, driven through the kernel (hex8_uniaxial_driver.h: the
// lateral stretch found each step so that the lateral faces are traction-free).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/elements/hex8.h"
#include "tests/unit/elements/hex8_uniaxial_driver.h"

namespace {

namespace el = crashlink::elements;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

}  // namespace

// sigma_xx follows sigma_y(eps_p) of the input curve within 1% (the return is exact on the curve,
// so the residual is the secant tolerance on the lateral stress), and eps_p matches the axial
// log strain minus the elastic strain, ln(lambda_x) - sigma_xx / E, within 1% once eps_p > 0.01
// (the midpoint integral of D_xx is the log strain to O(d eps^2)).
TEST(Hex8J2, UniaxialStressFollowsHardeningCurve) {
  const Material mat{
      "j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.05, 0.2}, {250e6, 350e6, 400e6}}};
  double final_ep = 0.0;
  int checked = 0;
  crashlink::testing::drive_hex8_uniaxial(
      mat, 0.3, 3000, 1e-6, 1e-6 * 250e6, [&](int s, double lx, const el::Hex8State& st) {
        const double sxx = st.stress[0], ep = st.eps_p[0];
        EXPECT_NEAR(st.stress[1], 0.0, 1e-5 * 250e6);
        EXPECT_NEAR(st.stress[2], 0.0, 1e-5 * 250e6);
        if (ep > 0.0) {
          EXPECT_NEAR(sxx, mat.hardening.yield(ep), 0.01 * mat.hardening.yield(ep)) << "step " << s;
        }
        if (ep > 0.01) {
          EXPECT_NEAR(ep, std::log(lx) - sxx / 210e9, 0.01 * ep) << "step " << s;
          ++checked;
        }
        final_ep = ep;
      });
  EXPECT_GT(checked, 2000);
  EXPECT_NEAR(final_ep, 0.3 - 400e6 / 210e9 - 0.0, 0.01 * 0.3);
}
