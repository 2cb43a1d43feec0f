// Closest-point projection: exact on flat quads and triangles (interior, edge and vertex
// regions), Gauss-Newton converged on a warped quad (residual orthogonal to the tangents), and
// the shape functions reproduce the closest point.
#include "solver/contact/projection.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace crashlink::contact;

namespace {
// Unit square in z = 0, counter-clockwise: normal +z.
const double kSquare[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
}  // namespace

TEST(Projection, FlatQuadInterior) {
  const double p[3] = {0.3, 0.7, 0.25};
  const auto pr = project_quad(kSquare, p);
  EXPECT_TRUE(pr.interior);
  EXPECT_NEAR(pr.xc[0], 0.3, 1e-14);  // exact for a flat parallelogram: round-off only
  EXPECT_NEAR(pr.xc[1], 0.7, 1e-14);
  EXPECT_NEAR(pr.xc[2], 0.0, 1e-14);
  EXPECT_NEAR(pr.normal[2], 1.0, 1e-14);
  EXPECT_NEAR(pr.N[0] + pr.N[1] + pr.N[2] + pr.N[3], 1.0, 1e-15);
  EXPECT_NEAR(pr.N[2], 0.3 * 0.7, 1e-14);  // bilinear weight of node (1,1)
}

TEST(Projection, FlatQuadEdgeAndVertex) {
  const double pe[3] = {1.2, 0.4, 0.1};  // beyond edge 1-2
  const auto e = project_quad(kSquare, pe);
  EXPECT_FALSE(e.interior);
  EXPECT_NEAR(e.xc[0], 1.0, 1e-15);
  EXPECT_NEAR(e.xc[1], 0.4, 1e-15);
  EXPECT_NEAR(e.N[0] + e.N[3], 0.0, 1e-15);  // only the edge's nodes carry weight
  EXPECT_NEAR(e.N[1], 0.6, 1e-15);
  const double pv[3] = {-0.5, -0.5, -0.2};  // beyond vertex 0
  const auto v = project_quad(kSquare, pv);
  EXPECT_FALSE(v.interior);
  EXPECT_NEAR(v.N[0], 1.0, 1e-15);
}

TEST(Projection, WarpedQuadIsStationary) {
  const double xa[12] = {0, 0, 0, 1, 0, 0.1, 1.1, 1, -0.05, 0, 0.9, 0.12};
  const double p[3] = {0.4, 0.55, 0.3};
  const auto pr = project_quad(xa, p);
  ASSERT_TRUE(pr.interior);
  // (p - x_c) is along the normal at the converged point: tangential residual ~ round-off.
  const double r[3] = {p[0] - pr.xc[0], p[1] - pr.xc[1], p[2] - pr.xc[2]};
  const double rn = r[0] * pr.normal[0] + r[1] * pr.normal[1] + r[2] * pr.normal[2];
  const double rt = std::sqrt(std::max(0.0, r[0] * r[0] + r[1] * r[1] + r[2] * r[2] - rn * rn));
  EXPECT_LT(rt, 1e-10);
  double x = 0.0;
  for (int a = 0; a < 4; ++a) x += pr.N[a] * xa[3 * a];
  EXPECT_NEAR(x, pr.xc[0], 1e-15);
}

TEST(Projection, TriangleRegions) {
  const double t[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const double pi[3] = {0.2, 0.3, -0.4};
  const auto a = project_triangle(t, pi);
  EXPECT_TRUE(a.interior);
  EXPECT_NEAR(a.N[1], 0.2, 1e-15);
  EXPECT_NEAR(a.N[2], 0.3, 1e-15);
  const double pe[3] = {0.8, 0.8, 0.0};  // beyond the hypotenuse
  const auto b = project_triangle(t, pe);
  EXPECT_FALSE(b.interior);
  EXPECT_NEAR(b.xc[0], 0.5, 1e-15);
  EXPECT_NEAR(b.N[0], 0.0, 1e-15);
}
