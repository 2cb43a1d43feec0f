#include <gtest/gtest.h>

#include <map>
#include <numbers>

#include "solver/model/mesh_generators.h"
#include "tests/unit/model/mesh_geometry.h"

namespace crashlink::model {
namespace {

using testing::corners;
using testing::quad_area;
using testing::quad_normal;

struct SphereStats {
  double area = 0.0;
  double min_outward = 1.0;  ///< smallest normal . radial direction at the quad centre
  double edge_ratio = 1.0;   ///< longest / shortest edge over the mesh
};

SphereStats make_sphere(Model& m, const Vec3& centre, double radius, int n) {
  Part p;
  p.name = "ball";
  p.material = 0;
  p.thickness_m = 1e-3;
  generate_sphere(m, std::move(p), {centre, radius, n});
  const Part& part = m.parts.back();
  SphereStats s;
  double emin = 1e300, emax = 0.0;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const auto x = corners<4>(m, part, e);
    s.area += quad_area(x);
    const Vec3 mid = 0.25 * (x[0] + x[1] + x[2] + x[3]);
    const Vec3 radial = (1.0 / norm(mid - centre)) * (mid - centre);
    s.min_outward = std::min(s.min_outward, dot(quad_normal(x), radial));
    for (std::size_t a = 0; a < 4; ++a) {
      const double l = norm(x[(a + 1) % 4] - x[a]);
      emin = std::min(emin, l);
      emax = std::max(emax, l);
    }
  }
  s.edge_ratio = emax / emin;
  return s;
}

TEST(GenerateSphere, CountsAndNodesOnTheSphere) {
  Model m;
  const Vec3 c{0.1, -0.2, 0.3};
  make_sphere(m, c, 0.0825, 6);
  EXPECT_EQ(m.nodes.count(), 6u * 36u + 2u);
  EXPECT_EQ(m.parts[0].element_count(), 6u * 36u);
  EXPECT_EQ(m.parts[0].kind, ElementKind::Shell4);
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    EXPECT_NEAR(norm(testing::node_x(m, static_cast<std::int32_t>(i)) - c), 0.0825, 1e-15);
}

// Every quad's normal points outward, and the surface is closed and consistently oriented: each
// directed edge a->b appears once, and its reverse b->a belongs to exactly one other quad.
TEST(GenerateSphere, OutwardNormalsAndClosedConsistentSurface) {
  Model m;
  const SphereStats s = make_sphere(m, {0, 0, 0}, 1.0, 5);
  EXPECT_GT(s.min_outward, 0.9);
  std::map<std::pair<int, int>, int> directed;
  const auto& conn = m.parts[0].connectivity;
  for (std::size_t e = 0; e < m.parts[0].element_count(); ++e)
    for (std::size_t a = 0; a < 4; ++a) ++directed[{conn[4 * e + a], conn[4 * e + (a + 1) % 4]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  EXPECT_EQ(directed.size(), 4u * 6u * 25u);
}

// Why 1 % at n = 8 (the plate_impact headform's order of resolution): the flat quads are
// inscribed (vertices on the sphere), so they lie inside it and their area falls short of
// 4 pi R^2. For a quad of angular half-width a, its plane sits at R cos(sqrt(2) a) from the centre
// and the radial projection of the sphere onto it scales areas by (d/R)^2 / cos^3(theta); averaged
// over the quad this is 1 - a^2 + O(a^4). The equiangular cube-sphere gives a = pi / (4 n), so the
// deficit is about (pi / (4 n))^2: 0.96 % at n = 8 (measured 0.83 %), 0.24 % at n = 16 (0.21 %).
// It must be positive, below 1 % at n = 8, and shrink as n^-2 (ratio 4 between n = 8 and 16).
TEST(GenerateSphere, AreaWithinOnePercentAndConvergesAtSecondOrder) {
  const double R = 0.0825, exact = 4.0 * std::numbers::pi * R * R;
  Model m8, m16;
  const SphereStats s8 = make_sphere(m8, {0, 0, 0}, R, 8);
  const SphereStats s16 = make_sphere(m16, {0, 0, 0}, R, 16);
  const double err8 = (exact - s8.area) / exact, err16 = (exact - s16.area) / exact;
  EXPECT_GT(err8, 0.0);  // inscribed: always below
  EXPECT_LT(err8, 0.01);
  EXPECT_NEAR(err8 / err16, 4.0, 0.3);
  // Good-quality quads: edge lengths within a factor 1.5 over the whole sphere (1.40 at n = 8;
  // the plain gnomonic map would give about 2).
  EXPECT_LT(s8.edge_ratio, 1.5);
}

}  // namespace
}  // namespace crashlink::model
