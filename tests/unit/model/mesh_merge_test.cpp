#include <gtest/gtest.h>

#include <set>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/node_merging.h"

namespace crashlink::model {
namespace {

Part hex_part(const std::string& name) {
  Part p;
  p.name = name;
  p.material = 0;
  return p;
}

// Two boxes sharing the face x = 1 (a 4 x 3 node grid): after merging, the second box uses the
// first box's nodes on that face, and its own nodes are renumbered without gaps.
TEST(MergeCoincidentNodes, SharedFaceIsMergedAndIdsStayContiguous) {
  Model m;
  generate_box(m, hex_part("a"), {{0, 0, 0}, {1, 1, 1}, {2, 3, 2}});
  const std::size_t first = m.nodes.count();  // 3*4*3 = 36
  // 1e-9 m off the shared face: within the tolerance.
  generate_box(m, hex_part("b"), {{1.0 + 1e-9, 0, 0}, {0.5, 1, 1}, {1, 3, 2}});
  ASSERT_EQ(m.nodes.count(), 36u + 24u);
  const std::size_t merged = merge_coincident_nodes(m, first, 1e-6);
  EXPECT_EQ(merged, 12u);
  EXPECT_EQ(m.nodes.count(), 48u);
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    EXPECT_EQ(m.nodes.id[i], static_cast<std::int64_t>(i) + 1);
  // Part b: 12 distinct nodes are old ones on x = 1, and they are exactly part a's x = 1 nodes.
  std::set<std::int32_t> shared;
  for (auto c : m.parts[1].connectivity)
    if (static_cast<std::size_t>(c) < first) shared.insert(c);
  ASSERT_EQ(shared.size(), 12u);
  for (auto c : shared) EXPECT_DOUBLE_EQ(m.nodes.x0[3 * static_cast<std::size_t>(c)], 1.0);
  for (auto c : m.parts[1].connectivity) EXPECT_LT(static_cast<std::size_t>(c), m.nodes.count());
}

TEST(MergeCoincidentNodes, NodesBeyondToleranceStaySeparate) {
  Model m;
  generate_box(m, hex_part("a"), {{0, 0, 0}, {1, 1, 1}, {1, 1, 1}});
  generate_box(m, hex_part("b"), {{1.001, 0, 0}, {1, 1, 1}, {1, 1, 1}});
  EXPECT_EQ(merge_coincident_nodes(m, 8, 1e-4), 0u);
  EXPECT_EQ(m.nodes.count(), 16u);
  EXPECT_EQ(merge_coincident_nodes(m, 8, 2e-3), 4u);
  EXPECT_EQ(m.nodes.count(), 12u);
  EXPECT_THROW(merge_coincident_nodes(m, 8, 0.0), ModelError);
}

// The hash grid scales: two 60 x 60 plates sharing an edge line merge in well under a second
// (the O(n^2) pairing would take ~13 million distance checks; this is a smoke check, not a bench).
TEST(MergeCoincidentNodes, LargePlatesSharingAnEdge) {
  Model m;
  Part p;
  p.name = "p";
  p.material = 0;
  p.thickness_m = 1e-3;
  generate_plate(m, p, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {60, 60}, 0.0});
  const std::size_t first = m.nodes.count();
  generate_plate(m, p, {{1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {60, 60}, 0.0});
  EXPECT_EQ(merge_coincident_nodes(m, first, 1e-6), 61u);
  EXPECT_EQ(m.nodes.count(), 2u * 61u * 61u - 61u);
}

}  // namespace
}  // namespace crashlink::model
