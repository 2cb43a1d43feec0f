#include <gtest/gtest.h>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"
#include "tests/unit/model/mesh_geometry.h"

namespace crashlink::model {
namespace {

using testing::corners;
using testing::hex_volume;
using testing::min_corner_jacobian;

Part hex_part(const std::string& name) {
  Part p;
  p.name = name;
  p.material = 0;
  return p;
}

// A box of parallelepiped hexahedra: volumes are exact up to round-off (1e-12 relative).
TEST(GenerateBox, CountsIdsOrientationAndVolume) {
  Model m;
  const BoxMesh box{{1.0, -2.0, 0.5}, {0.3, 0.2, 0.1}, {3, 4, 5}};
  const int p = generate_box(m, hex_part("block"), box);
  ASSERT_EQ(p, 0);
  EXPECT_EQ(m.nodes.count(), 4u * 5u * 6u);
  const Part& part = m.parts[0];
  EXPECT_EQ(part.kind, ElementKind::Hex8);
  ASSERT_EQ(part.element_count(), 60u);
  EXPECT_EQ(m.nodes.id.front(), 1);
  EXPECT_EQ(m.nodes.id.back(), 120);
  EXPECT_EQ(part.element_id.front(), 1);
  EXPECT_EQ(part.element_id.back(), 60);
  double volume = 0.0;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const auto x = corners<8>(m, part, e);
    EXPECT_GT(min_corner_jacobian(x), 0.0) << "element " << e;
    volume += hex_volume(x);
  }
  EXPECT_NEAR(volume, 0.3 * 0.2 * 0.1, 1e-12 * 0.006);
  // Corners land exactly on the requested bounds.
  double xmax = -1e300, zmin = 1e300;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    xmax = std::max(xmax, m.nodes.x0[3 * i]);
    zmin = std::min(zmin, m.nodes.x0[3 * i + 2]);
  }
  EXPECT_EQ(xmax, 1.3);
  EXPECT_EQ(zmin, 0.5);
}

TEST(GenerateBox, SecondPartContinuesNodeAndElementIds) {
  Model m;
  generate_box(m, hex_part("a"), {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});
  const int p = generate_box(m, hex_part("b"), {{2, 0, 0}, {1, 1, 1}, {1, 1, 1}});
  ASSERT_EQ(p, 1);
  EXPECT_EQ(m.nodes.count(), 27u + 8u);
  EXPECT_EQ(m.nodes.id[27], 28);
  EXPECT_EQ(m.parts[1].element_id[0], 9);
  for (auto c : m.parts[1].connectivity) EXPECT_GE(c, 27);  // no sharing without merging
}

TEST(GenerateBox, RejectsZeroDivisionsOrSize) {
  Model m;
  EXPECT_THROW(generate_box(m, hex_part("a"), {{0, 0, 0}, {1, 1, 1}, {0, 1, 1}}), ModelError);
  EXPECT_THROW(generate_box(m, hex_part("a"), {{0, 0, 0}, {1, -1, 1}, {1, 1, 1}}), ModelError);
}

TEST(GenerateBar, AlongEachAxisPositiveAndRightExtent) {
  for (int axis = 0; axis < 3; ++axis) {
    Model m;
    BarMesh bar;
    bar.origin_m = {0.1, 0.2, 0.3};
    bar.axis = axis;
    bar.length_m = 2.0;
    bar.cross_section_m = {0.02, 0.05};
    bar.elements = 10;
    generate_bar(m, hex_part("bar"), bar);
    const Part& part = m.parts[0];
    ASSERT_EQ(part.element_count(), 10u);
    EXPECT_EQ(m.nodes.count(), 44u);
    double volume = 0.0;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const auto x = corners<8>(m, part, e);
      EXPECT_GT(min_corner_jacobian(x), 0.0) << "axis " << axis << " element " << e;
      volume += hex_volume(x);
    }
    EXPECT_NEAR(volume, 2.0 * 0.02 * 0.05, 1e-12);
    const auto a = static_cast<std::size_t>(axis);
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      lo = std::min(lo, m.nodes.x0[3 * i + a]);
      hi = std::max(hi, m.nodes.x0[3 * i + a]);
    }
    EXPECT_NEAR(lo, bar.origin_m[a], 1e-15);
    EXPECT_NEAR(hi, bar.origin_m[a] + 2.0, 1e-15);
  }
}

}  // namespace
}  // namespace crashlink::model
