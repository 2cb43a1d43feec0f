#include <gtest/gtest.h>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"
#include "tests/unit/model/mesh_geometry.h"

namespace crashlink::model {
namespace {

using testing::corners;
using testing::min_corner_turn;
using testing::quad_area;
using testing::quad_normal;

Part shell_part() {
  Part p;
  p.name = "plate";
  p.material = 0;
  p.thickness_m = 1e-3;
  return p;
}

/// Total area; checks every normal is the unit vector n and every quad convex.
double check_plate(const Model& m, const Vec3& n) {
  const Part& part = m.parts.back();
  double area = 0.0;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const auto x = corners<4>(m, part, e);
    EXPECT_NEAR(dot(quad_normal(x), n), 1.0, 1e-12) << "element " << e;
    EXPECT_GT(min_corner_turn(x, n), 0.0) << "element " << e;
    area += quad_area(x);
  }
  return area;
}

// Flat meshes: areas exact up to round-off.
TEST(GeneratePlate, AxisNormalCountsAndArea) {
  Model m;
  PlateMesh plate;
  plate.origin_m = {-0.2, -0.2, 0.0};
  plate.edge1_m = {0.4, 0.0, 0.0};
  plate.edge2_m = {0.0, 0.3, 0.0};
  plate.divisions = {8, 6};
  generate_plate(m, shell_part(), plate);
  EXPECT_EQ(m.nodes.count(), 9u * 7u);
  EXPECT_EQ(m.parts[0].element_count(), 48u);
  EXPECT_EQ(m.parts[0].kind, ElementKind::Shell4);
  EXPECT_NEAR(check_plate(m, {0, 0, 1}), 0.12, 1e-14);
}

TEST(GeneratePlate, SkewEdgesGiveParallelogramWithNormalE1CrossE2) {
  Model m;
  PlateMesh plate;
  plate.edge1_m = {0.0, 1.0, 1.0};
  plate.edge2_m = {1.0, 0.0, 0.5};
  plate.divisions = {5, 7};
  generate_plate(m, shell_part(), plate);
  const Vec3 c = cross(plate.edge1_m, plate.edge2_m);
  EXPECT_NEAR(check_plate(m, (1.0 / norm(c)) * c), norm(c), 1e-12);
}

// Moving interior nodes in the plane leaves the total area unchanged (boundary fixed) and, with
// amplitude 0.3 element sizes, every quad stays convex.
TEST(GeneratePlate, DistortedPlateKeepsAreaAndConvexity) {
  Model m;
  PlateMesh plate;
  plate.edge1_m = {1.0, 0.0, 0.0};
  plate.edge2_m = {0.0, 1.0, 0.0};
  plate.divisions = {10, 10};
  plate.distort = 0.3;
  generate_plate(m, shell_part(), plate);
  EXPECT_NEAR(check_plate(m, {0, 0, 1}), 1.0, 1e-12);
  // Really distorted: an interior node is off the lattice.
  const std::size_t mid = 5 + 11 * 5;
  EXPECT_GT(std::abs(m.nodes.x0[3 * mid] - 0.5) + std::abs(m.nodes.x0[3 * mid + 1] - 0.5), 1e-4);
  // Deterministic: the same mesh again.
  Model again;
  generate_plate(again, shell_part(), plate);
  EXPECT_EQ(again.nodes.x0, m.nodes.x0);
}

TEST(GeneratePlate, RejectsParallelEdges) {
  Model m;
  PlateMesh plate;
  plate.edge1_m = {1.0, 0.0, 0.0};
  plate.edge2_m = {2.0, 0.0, 0.0};
  plate.divisions = {2, 2};
  EXPECT_THROW(generate_plate(m, shell_part(), plate), ModelError);
}

}  // namespace
}  // namespace crashlink::model
