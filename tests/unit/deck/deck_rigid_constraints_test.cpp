// *CONSTRAINED_NODAL_RIGID_BODY, *CONSTRAINED_EXTRA_NODES_NODE/_SET and *CONSTRAINED_RIGID_BODIES
// read into the model's rigid bodies (docs/decks.md "Keywords"), and their mistakes.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

class DeckRigidConstraints : public testing::DeckLinesTest {};

/// two_cubes() with the upper cube rigid (part 2, *MAT_RIGID 2) and a third, rigid, cube part 3
/// sharing its material, plus `more`.
std::vector<std::string> rigid_cubes(const std::vector<std::string>& more) {
  auto d = testing::two_cubes();
  for (auto& l : d)
    if (l == "         2         1         1") l = "         2         2         2";
  d.insert(d.end(),
           {"*SECTION_SOLID", "         2         1", "*MAT_RIGID",
            "         2   7.85e-9  210000.0       0.3", "*NODE",
            "      17             0.0             0.0             3.0",
            "      18             1.0             0.0             3.0",
            "      19             0.0             1.0             3.0",
            "      20             1.0             1.0             3.0",
            "      21             0.0             0.0             4.0",
            "      22             1.0             0.0             4.0",
            "      23             0.0             1.0             4.0",
            "      24             1.0             1.0             4.0", "*ELEMENT_SOLID",
            "       3       3      17      18      20      19      21      22      24      23",
            "*PART", "top", "         3         2         2"});
  d.insert(d.end(), more.begin(), more.end());
  return d;
}

TEST_F(DeckRigidConstraints, NodalBodyExtraNodesAndMergedBodies) {
  DeckRead r;
  ASSERT_EQ(
      read(rigid_cubes(
               {"*SET_NODE_LIST", "         7", "         1         2         3",
                "*CONSTRAINED_NODAL_RIGID_BODY_TITLE", "bolt", "       100         0         7",
                "*CONSTRAINED_EXTRA_NODES_NODE", "         2         5", "*SET_NODE_LIST",
                "         8", "         6         7", "*CONSTRAINED_EXTRA_NODES_SET",
                "         3         8", "*CONSTRAINED_RIGID_BODIES", "         2         3"}),
           &r),
      "");
  const auto& b = r.model.rigid_bodies;
  ASSERT_EQ(b.size(), 2u) << "part 3's body merged into part 2's";
  EXPECT_EQ(b[0].name, "upper");
  EXPECT_EQ(b[0].parts.size(), 2u);
  const auto ids = [&](const model::RigidBody& rb) {
    std::vector<std::int64_t> out;
    for (auto c : rb.nodes) out.push_back(r.model.nodes.id[static_cast<std::size_t>(c)]);
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(ids(b[0]), (std::vector<std::int64_t>{5, 6, 7})) << "its own extra node, part 3's";
  EXPECT_EQ(b[1].name, "bolt");
  EXPECT_TRUE(b[1].parts.empty());
  EXPECT_EQ(ids(b[1]), (std::vector<std::int64_t>{1, 2, 3}));
}

// A velocity on the deformable part sets the nodal rigid body in it moving (its nodes follow it).
TEST_F(DeckRigidConstraints, NodalBodyTakesItsPartsVelocity) {
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes_with(
                     {"*SET_NODE_LIST", "         7", "         1         2         3",
                      "*CONSTRAINED_NODAL_RIGID_BODY", "       100         0         7",
                      "*INITIAL_VELOCITY_GENERATION", "         1         2       0.0    1000.0",
                      "         0         0         0         0         0         0"}),
                 &r),
            "");
  ASSERT_EQ(r.model.rigid_bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(r.model.rigid_bodies[0].velocity_m_s[0], 1.0);  // 1000 mm/s
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  EXPECT_EQ(r.model.initial_velocities[0].nodes.size(), 5u) << "the body's three nodes left out";
}

// *CONSTRAINED_SPOTWELD(_ID): a breakable body of two nodes, strengths in N (mm-t-s: N).
TEST_F(DeckRigidConstraints, SpotWeldsAreBreakableBodiesOfTwoNodes) {
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes_with(
                     {"*CONSTRAINED_SPOTWELD_ID", "        40",
                      "         7        11    1500.0    2500.0       2.0       3.0    0.0005",
                      "*CONSTRAINED_SPOTWELD", "         8        12"}),
                 &r),
            "");
  const auto& b = r.model.rigid_bodies;
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].name, "spotweld_40");
  EXPECT_EQ(r.model.nodes.id[static_cast<std::size_t>(b[0].nodes[0])], 7);
  EXPECT_EQ(r.model.nodes.id[static_cast<std::size_t>(b[0].nodes[1])], 11);
  EXPECT_DOUBLE_EQ(b[0].failure.normal_N, 1500.0);
  EXPECT_DOUBLE_EQ(b[0].failure.shear_N, 2500.0);
  EXPECT_DOUBLE_EQ(b[0].failure.exp_n, 2.0);
  EXPECT_DOUBLE_EQ(b[0].failure.exp_m, 3.0);
  EXPECT_DOUBLE_EQ(b[0].failure.time_s, 0.0005);
  EXPECT_EQ(b[1].name, "spotweld_41");  // unnumbered: above every WID of the deck
  EXPECT_FALSE(b[1].failure.any()) << "no strength, no time: a link that holds";
}

// A wall over every node (NSID 0) leaves out the nodes that follow a body, welds' too.
TEST_F(DeckRigidConstraints, WallLeavesOutWeldNodes) {
  DeckRead r;
  ASSERT_EQ(
      read(testing::two_cubes_with({"*CONSTRAINED_SPOTWELD", "         7        11",
                                    "*RIGIDWALL_PLANAR", "         0",
                                    "       0.0       0.0      -1.0       0.0       0.0       "
                                    "0.0"}),
           &r),
      "");
  ASSERT_EQ(r.model.rigid_walls.size(), 1u);
  const auto& w = r.model.rigid_walls[0].nodes;
  EXPECT_EQ(w.size(), 14u) << "16 nodes less the weld's two";
  for (auto c : r.model.rigid_bodies[0].nodes) EXPECT_EQ(std::count(w.begin(), w.end(), c), 0);
}

TEST_F(DeckRigidConstraints, MistakesNameTheirField) {
  struct Case {
    std::vector<std::string> lines;
    std::string message;
  };
  const Case cases[] = {
      {{"*SET_NODE_LIST", "         7", "         1         2", "*CONSTRAINED_NODAL_RIGID_BODY",
        "         1         0         7"},
       "*CONSTRAINED_NODAL_RIGID_BODY field PID (columns 1-10) = 1: 1 is a *PART's id"},
      {{"*CONSTRAINED_NODAL_RIGID_BODY", "       100         0         9"},
       "field NSID (columns 21-30) = 9: node set 9 is not defined"},
      {{"*SET_NODE_LIST", "         7", "         1         2", "*CONSTRAINED_NODAL_RIGID_BODY",
        "       100         0         7         0         0         1"},
       "field DRFLAG (columns 51-60) = 1: releasing translations (DRFLAG) is not computed"},
      {{"*CONSTRAINED_EXTRA_NODES_NODE", "         1         5"},
       "*CONSTRAINED_EXTRA_NODES_NODE field PID (columns 1-10) = 1: part 1 is not rigid"},
      {{"*CONSTRAINED_EXTRA_NODES_NODE", "         2         5         1"},
       "field IFLAG (columns 21-30) = 1: updating a *PART_INERTIA body"},
      {{"*CONSTRAINED_RIGID_BODIES", "         2         9"},
       "*CONSTRAINED_RIGID_BODIES field PIDC (columns 11-20) = 9: part 9 is not defined"},
      {{"*CONSTRAINED_SPOTWELD", "         1         5    1000.0"},
       "*CONSTRAINED_SPOTWELD field N (columns 41-50) = (blank): the normal term's exponent must "
       "be > 0"},
      {{"*CONSTRAINED_SPOTWELD",
        "         1         5       0.0       0.0       0.0       0.0       0.0      0.05"},
       "field EP (columns 71-80) = 0.05: failure at a plastic strain (EP) is not computed"},
      {{"*CONSTRAINED_SPOTWELD", "         1         1"},
       "field N2 (columns 11-20) = 1: is N1; fix: weld two distinct nodes"},
  };
  for (const auto& c : cases) {
    const std::string msg = read(rigid_cubes(c.lines));
    EXPECT_NE(msg.find(c.message), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace crashlink::deck
