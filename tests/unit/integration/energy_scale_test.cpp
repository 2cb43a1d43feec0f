// The integral of a load curve's magnitude (integration/energy_scale.h), which sizes the energy a
// load puts into a model: exact for piecewise-linear curves, constant outside their points.
#include "solver/integration/energy_scale.h"

#include <gtest/gtest.h>

#include <cmath>

using crashlink::integration::integral_of_magnitude;
using crashlink::model::Curve;

TEST(IntegralOfMagnitude, IsExactForPiecewiseLinearCurves) {
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve::constant(-3.0), 2.0), 6.0);
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve{}, 2.0), 0.0);
  // -1 at 0 to +1 at 2: two triangles of area 1/2
  const Curve ramp{{0.0, 2.0}, {-1.0, 1.0}};
  EXPECT_DOUBLE_EQ(integral_of_magnitude(ramp, 2.0), 1.0);
  // up to t = 1, the root: one triangle
  EXPECT_DOUBLE_EQ(integral_of_magnitude(ramp, 1.0), 0.5);
  // past the last point the curve holds its last value: 1 + 1 x 3
  EXPECT_DOUBLE_EQ(integral_of_magnitude(ramp, 5.0), 4.0);
  // -1 at 0 to +3 at 4 (root at t = 1): 1/2 + 3 x 3 / 2
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve{{0.0, 4.0}, {-1.0, 3.0}}, 4.0), 5.0);
  // a curve starting at t = 1 with value 2: 2 x 1 before it, then the trapezoid to 0 at t = 3
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve{{1.0, 3.0}, {2.0, 0.0}}, 3.0), 2.0 + 2.0);
  // a pulse: 0, 10 N at 1 ms, 0 at 2 ms, then nothing: 10 mN s whatever the end after it
  const Curve pulse{{0.0, 1e-3, 2e-3}, {0.0, 10.0, 0.0}};
  EXPECT_NEAR(integral_of_magnitude(pulse, 5e-3), 1e-2, 1e-17);
  EXPECT_NEAR(integral_of_magnitude(pulse, 1e-3), 5e-3, 1e-17);
  EXPECT_DOUBLE_EQ(integral_of_magnitude(pulse, 0.0), 0.0);
  // points before t = 0 count from 0 on: -2 at -1 s to +2 at +1 s, over [0, 1]: 0 to 2
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve{{-1.0, 1.0}, {-2.0, 2.0}}, 1.0), 1.0);
  // a root inside a segment cut by the end time: -1 at 0 to +3 at 4, over [0, 2] (value 1)
  EXPECT_DOUBLE_EQ(integral_of_magnitude(Curve{{0.0, 4.0}, {-1.0, 3.0}}, 2.0), 0.5 + 0.5);
  // a long tabulated curve, 10^6 points of |sin| over [0, pi] (and 0 after): one pass over
  // them (a search from the start for each point took minutes)
  Curve sine;
  const std::size_t n = 1000001;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 3.141592653589793 * static_cast<double>(i) / static_cast<double>(n - 1);
    sine.t_s.push_back(t);
    sine.value.push_back(std::sin(t));
  }
  EXPECT_NEAR(integral_of_magnitude(sine, 4.0), 2.0, 1e-9);
}
