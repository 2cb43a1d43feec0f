// Finite and geometric rigid walls, a rigid part's prescribed motion (velocity or displacement),
// *MAT_RIGID constraints and shell sets as contact surfaces, read into the model in SI
// (docs/decks.md "Keywords"), and their mistakes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

class DeckWallsMotions : public testing::DeckLinesTest {};

/// two_cubes() with the upper cube (part 2) of *MAT_RIGID 2 (card 2: `rigid_card2`), + `more`.
std::vector<std::string> rigid_upper(const std::vector<std::string>& more,
                                     const std::string& rigid_card2 = "") {
  auto d = testing::two_cubes();
  for (auto& l : d)
    if (l == "         2         1         1") l = "         2         2         2";
  d.insert(d.end(), {"*SECTION_SOLID", "         2         1", "*MAT_RIGID",
                     "         2   7.85e-9  210000.0       0.3"});
  if (!rigid_card2.empty()) d.push_back(rigid_card2);
  d.insert(d.end(), more.begin(), more.end());
  return d;
}

TEST_F(DeckWallsMotions, FinitePlaneFlatAndCylinderInSI) {
  DeckRead r;
  ASSERT_EQ(
      read(testing::two_cubes_with(
               {"*RIGIDWALL_PLANAR_FINITE_ID", "         3pad", "         0",
                "       1.0       2.0      -1.0       1.0       2.0       5.0",
                "       4.0       2.0      -1.0      20.0      10.0", "*RIGIDWALL_GEOMETRIC_FLAT",
                "         0", "       0.0       0.0      -2.0       0.0       0.0      -1.0",
                "       0.0       3.0      -2.0      30.0      40.0",
                "*RIGIDWALL_GEOMETRIC_CYLINDER_ID", "         5roller", "         0",
                "       0.0       0.0      -9.0       8.0       0.0      -9.0",
                "       4.0      50.0", "*RIGIDWALL_PLANAR_MOVING_FINITE", "         0",
                "       0.0       0.0      -3.0       0.0       0.0      -2.0",
                "       0.0       0.0       0.0       0.0       0.0", "    0.0010    1000.0"}),
           &r),
      "");
  const auto& w = r.model.rigid_walls;
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w[0].name, "pad");
  EXPECT_EQ(w[0].shape, model::RigidWall::Shape::Plane);
  EXPECT_TRUE(w[0].finite());
  EXPECT_DOUBLE_EQ(w[0].point_m[0], 1e-3);
  EXPECT_DOUBLE_EQ(w[0].normal[2], 1.0);
  EXPECT_DOUBLE_EQ(w[0].edge[0], 1.0) << "from the tail to XHEV";
  EXPECT_DOUBLE_EQ(w[0].length_m, 0.02);
  EXPECT_DOUBLE_EQ(w[0].width_m, 0.01);
  EXPECT_DOUBLE_EQ(w[1].edge[1], 1.0);
  EXPECT_DOUBLE_EQ(w[1].length_m, 0.03);
  EXPECT_DOUBLE_EQ(w[1].width_m, 0.04);
  EXPECT_EQ(w[2].name, "roller");
  EXPECT_EQ(w[2].shape, model::RigidWall::Shape::Cylinder);
  EXPECT_DOUBLE_EQ(w[2].normal[0], 1.0) << "the axis from tail to head";
  EXPECT_DOUBLE_EQ(w[2].radius_m, 0.004);
  EXPECT_DOUBLE_EQ(w[2].length_m, 0.05);
  // LENL = LENM = 0 on _FINITE: infinite (LS-DYNA); the moving card after the finite one
  EXPECT_FALSE(w[3].finite());
  EXPECT_DOUBLE_EQ(w[3].mass_kg, 1.0);
  EXPECT_DOUBLE_EQ(w[3].velocity_m_s, 1.0);
}

TEST_F(DeckWallsMotions, RigidPartMotionAndConstraints) {
  DeckRead r;
  ASSERT_EQ(read(rigid_upper({"*DEFINE_CURVE", "         7", "0.0,0.0", "1.0e-3,2.0", "3.0e-3,2.0",
                              "*DEFINE_CURVE", "         8", "0.0,0.0", "1.0e-3,1000.0",
                              "*BOUNDARY_PRESCRIBED_MOTION_RIGID",
                              "         2         3         2         7",
                              "         2         1         0         8       0.5"},
                             "       1.0         2         7"),
                 &r),
            "");
  ASSERT_EQ(r.model.rigid_bodies.size(), 1u);
  EXPECT_EQ(r.model.rigid_bodies[0].fixed, model::kUy | model::kRx | model::kRy | model::kRz)
      << "CON1 2: y; CON2 7: all rotations";
  const auto& pv = r.model.prescribed_velocities;
  ASSERT_EQ(pv.size(), 2u);
  EXPECT_EQ(pv[0].rigid_body, 0);
  EXPECT_TRUE(pv[0].nodes.empty());
  EXPECT_EQ(pv[0].dof, 2);
  // VAD 2: 2 mm over 1 ms, then held: 2 m/s on the first segment, 0 on the second and after
  EXPECT_NEAR(pv[0].velocity.at(0.5e-3), 2.0, 1e-12);
  EXPECT_NEAR(pv[0].velocity.at(2.0e-3), 0.0, 1e-12);
  EXPECT_NEAR(pv[0].velocity.at(5.0e-3), 0.0, 1e-12);
  // its integral is the displacement curve at its points, to 1e-6 of the segment
  double d = 0.0;
  const int n = 300000;
  for (int k = 0; k < n; ++k) d += pv[0].velocity.at((k + 0.5) * 3e-3 / n) * 3e-3 / n;
  EXPECT_NEAR(d, 2e-3, 1e-8);
  EXPECT_EQ(pv[1].dof, 0);
  EXPECT_NEAR(pv[1].velocity.at(1e-3), 0.5, 1e-12) << "SF 0.5 x 1000 mm/s";
}

// CON1/CON2 codes 4-6 (two axes each) and a body's rotation driven by a displacement (VAD 2).
TEST_F(DeckWallsMotions, RigidCodesOfTwoAxesAndARotationDriven) {
  DeckRead r;
  ASSERT_EQ(read(rigid_upper({"*DEFINE_CURVE", "         7", "0.0,0.0", "1.0e-3,0.5",
                              "*BOUNDARY_PRESCRIBED_MOTION_RIGID",
                              "         2         6         2         7"},
                             "       1.0         5         6"),
                 &r),
            "");
  EXPECT_EQ(r.model.rigid_bodies[0].fixed, model::kUy | model::kUz | model::kRz | model::kRx)
      << "CON1 5: y and z; CON2 6: z and x";
  ASSERT_EQ(r.model.prescribed_velocities.size(), 1u);
  EXPECT_EQ(r.model.prescribed_velocities[0].dof, 4) << "DOF 6: about y";
  EXPECT_NEAR(r.model.prescribed_velocities[0].velocity.at(0.5e-3), 500.0, 1e-9)
      << "0.5 rad over 1 ms";
}

// *INITIAL_VELOCITY_GENERATION with OMEGA: a spin about the axis through card 2's point, on the
// deformable cube's nodes (v = v0 + omega x (x - c)) and on the rigid cube's body (its velocity
// that of the axis point, its angular velocity omega).
TEST_F(DeckWallsMotions, VelocityGenerationWithASpin) {
  DeckRead r;
  ASSERT_EQ(read(rigid_upper({"*INITIAL_VELOCITY_GENERATION",
                              "         1         2     100.0    1000.0       0.0       0.0",
                              "       0.5       0.5       0.0       0.0       0.0       2.0",
                              "*INITIAL_VELOCITY_GENERATION",
                              "         2         2      50.0       0.0       0.0       0.0",
                              "       0.0       0.0       0.0       1.0       0.0       0.0"}),
                 &r),
            "");
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  const auto& iv = r.model.initial_velocities[0];
  EXPECT_DOUBLE_EQ(iv.angular_velocity_rad_s[2], 100.0) << "about +z, 100 rad/s";
  EXPECT_DOUBLE_EQ(iv.centre_m[0], 0.5e-3);
  // node 1 at (0, 0, 0): 1 m/s + 100 z x (-0.5, -0.5, 0) mm = (1 + 0.05, -0.05, 0) m/s
  const Vec3 v1 = iv.at({0.0, 0.0, 0.0});
  EXPECT_NEAR(v1[0], 1.05, 1e-12);
  EXPECT_NEAR(v1[1], -0.05, 1e-12);
  const auto& b = r.model.rigid_bodies[0];
  EXPECT_TRUE(b.velocity_at_point);
  EXPECT_DOUBLE_EQ(b.angular_velocity_rad_s[0], 50.0);
  EXPECT_EQ(b.velocity_point_m, (Vec3{0.0, 0.0, 0.0}));
  // mistakes: a spin in a local system, an axis of no direction
  EXPECT_NE(
      read(testing::two_cubes_with(
               {"*DEFINE_COORDINATE_SYSTEM", "         1       0.0       0.0       0.0       1.0",
                "       0.0       1.0       0.0", "*INITIAL_VELOCITY_GENERATION",
                "         1         2     100.0       0.0       0.0"
                "       0.0         0         1",
                "       0.0       0.0       0.0       0.0       0.0"
                "       1.0"}))
          .find("field ICID (columns 71-80) = 1: a spin (OMEGA) with a local system"),
      std::string::npos);
  EXPECT_NE(read(testing::two_cubes_with(
                     {"*INITIAL_VELOCITY_GENERATION",
                      "         1         2     100.0       0.0       0.0       0.0",
                      "       0.0       0.0       0.0       0.0       0.0       0.0"}))
                .find("field NX (columns 31-40) = 0.0: the spin's axis (NX, NY, NZ) is the zero "
                      "vector"),
            std::string::npos);
}

// Records of several cards: a blank card within one is a card of defaults (a weld that never
// fails, a body at rest, a body held by nothing), several records follow each other, a record cut
// short is refused; IRIGID 1 sets a nodal _INERTIA body's velocity; one node twice in a weld's set
// and a WID twice are refused; an unnumbered weld is named above every WID.
TEST_F(DeckWallsMotions, MultiCardRecordsAndTheirMistakes) {
  DeckRead r;
  const std::vector<std::string> sets = {"*SET_NODE_LIST", "         7", "         1         9",
                                         "*SET_NODE_LIST", "         8", "         2        10",
                                         "*SET_NODE_LIST", "         5", "         3         4",
                                         "*SET_NODE_LIST", "         6", "        11        12"};
  auto d = testing::two_cubes_with(sets);
  d.insert(d.end(),
           {"*CONSTRAINED_GENERALIZED_WELD_SPOT",
            "         7",
            "",
            "         8",
            "    1.0e-3       0.0     500.0       0.0       2.0",
            "*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_TITLE",
            "first",
            "       100         0         5",
            "       0.5       0.5       0.5     0.001         0         0",
            "       0.1       0.0       0.0       0.1       0.0       0.1",
            "",
            "second",
            "       101         0         6",
            "       0.5       0.5       1.5     0.001         0         0",
            "       0.1       0.0       0.0       0.1       0.0       0.1",
            "    1000.0       0.0       0.0       0.0       0.0       0.0",
            "*CONSTRAINED_SPOTWELD_ID",
            "         5",
            "        13        14",
            "*CONSTRAINED_SPOTWELD",
            "        15        16",
            "*SET_NODE_LIST",
            "        20",
            "        11",
            "*INITIAL_VELOCITY_GENERATION",
            "        20         3       0.0     200.0       0.0       0.0",
            "       0.0       0.0       0.0       0.0       0.0       0.0         0         1"});
  ASSERT_EQ(read(d, &r), "");
  const auto& b = r.model.rigid_bodies;
  ASSERT_EQ(b.size(), 6u);
  EXPECT_EQ(b[0].name, "spotweld_6") << "unnumbered: above WID 5";
  EXPECT_FALSE(b[0].failure.any()) << "a blank failure card: never fails";
  EXPECT_EQ(b[1].name, "spotweld_7");
  EXPECT_DOUBLE_EQ(b[1].failure.shear_N, 0.0);
  EXPECT_DOUBLE_EQ(b[1].failure.normal_N, 500.0);
  EXPECT_EQ(b[2].name, "first");
  EXPECT_DOUBLE_EQ(b[2].velocity_m_s[0], 0.0) << "a blank velocity card: at rest";
  EXPECT_EQ(b[3].name, "second");
  EXPECT_DOUBLE_EQ(b[3].mass_kg, 1.0);
  EXPECT_DOUBLE_EQ(b[3].velocity_m_s[0], 0.2) << "IRIGID 1 sets an _INERTIA body's velocity";
  EXPECT_EQ(b[4].name, "spotweld_5");
  EXPECT_EQ(b[5].name, "spotweld_8");
  // mistakes
  EXPECT_NE(read(testing::two_cubes_with({"*CONSTRAINED_NODAL_RIGID_BODY_SPC",
                                          "       100         0"
                                          "         7"}))
                .find("its last record is cut short"),
            std::string::npos);
  EXPECT_NE(read(testing::two_cubes_with({"*SET_NODE_LIST", "         7", "         1         1",
                                          "*CONSTRAINED_GENERALIZED_WELD_SPOT", "         7",
                                          "    1.0e-3"}))
                .find("the weld's two nodes are one node"),
            std::string::npos);
  EXPECT_NE(
      read(testing::two_cubes_with({"*CONSTRAINED_SPOTWELD_ID", "         5",
                                    "         1         2", "         5", "         3         4"}))
          .find("spot weld 5 is already defined"),
      std::string::npos);
  EXPECT_NE(read(testing::two_cubes_with(
                     {"*INITIAL_VELOCITY_GENERATION",
                      "         1         2     100.0       0.0       0.0       0.0",
                      "       0.0       0.0       0.0    -999.0         1         2"}))
                .find("an axis by two nodes (NX = -999"),
            std::string::npos);
}

TEST_F(DeckWallsMotions, ShellSetIsASlaveSurface) {
  DeckRead r;
  ASSERT_EQ(
      read(testing::two_cubes_with({"*NODE",
                                    "      31             0.0             0.0             3.0",
                                    "      32             1.0             0.0             3.0",
                                    "      33             1.0             1.0             3.0",
                                    "      34             0.0             1.0             3.0",
                                    "      35             2.0             0.0             3.0",
                                    "      36             2.0             1.0             3.0",
                                    "*ELEMENT_SHELL",
                                    "      50       3      31      32      33      34",
                                    "      51       3      32      35      36      33",
                                    "*PART",
                                    "sheet",
                                    "         3         3         1",
                                    "*SECTION_SHELL",
                                    "         3         2  0.833333         3",
                                    "       1.0",
                                    "*SET_SHELL_LIST",
                                    "         4",
                                    "        51",
                                    "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
                                    "         4         2         1"
                                    "         3"}),
           &r),
      "");
  ASSERT_EQ(r.model.contacts.size(), 1u);
  const auto& c = r.model.contacts[0];
  ASSERT_EQ(c.slave_faces.size(), 4u) << "shell 51's face only";
  std::vector<std::int64_t> ids;
  for (auto i : c.slave_faces) ids.push_back(r.model.nodes.id[static_cast<std::size_t>(i)]);
  EXPECT_EQ(ids, (std::vector<std::int64_t>{32, 35, 36, 33}));
  EXPECT_EQ(c.slave_nodes.size(), 4u);
}

TEST_F(DeckWallsMotions, MistakesNameTheirField) {
  struct Case {
    std::vector<std::string> lines;
    std::string message;
  };
  const std::string card1 = "         0";
  const std::string card2 = "       0.0       0.0      -1.0       0.0       0.0       0.0";
  const Case cases[] = {
      {{"*RIGIDWALL_PLANAR_FINITE", card1, card2,
        "       0.0       0.0       1.0      10.0      10.0"},
       "*RIGIDWALL_PLANAR_FINITE field XHEV (columns 1-10) = 0.0: the edge l from the tail"},
      {{"*RIGIDWALL_PLANAR_FINITE", card1, card2, "       1.0       0.0      -1.0      10.0"},
       "field LENM (columns 41-50) = (blank): a finite wall needs both lengths > 0"},
      {{"*RIGIDWALL_GEOMETRIC_CYLINDER", card1, card2, "       0.0"},
       "*RIGIDWALL_GEOMETRIC_CYLINDER field RADCYL (columns 1-10) = 0.0: the cylinder needs its "
       "radius"},
      {{"*RIGIDWALL_GEOMETRIC_CYLINDER", card1, card2}, "*RIGIDWALL_GEOMETRIC_CYLINDER"},
      {{"*RIGIDWALL_GEOMETRIC_CYLINDER_MOTION", card1, card2, "       1.0"},
       "*RIGIDWALL_GEOMETRIC_CYLINDER_MOTION: not supported"},
      {{"*DEFINE_CURVE", "         7", "0.0,0.0", "1.0,1.0", "*BOUNDARY_PRESCRIBED_MOTION_RIGID",
        "         1         3         0         7"},
       "*BOUNDARY_PRESCRIBED_MOTION_RIGID field PID (columns 1-10) = 1: part 1 is not a rigid "
       "part"},
      {{"*DEFINE_CURVE", "         7", "0.0,0.0", "1.0,1.0", "*BOUNDARY_PRESCRIBED_MOTION_SET",
        "         1         3         1         7"},
       "field VAD (columns 21-30) = 1: crashlink prescribes a velocity (VAD 0) or a displacement"},
      {{"*SET_NODE_LIST", "         1", "         1", "*DEFINE_CURVE", "         7", "0.0,1.0",
        "1.0,1.0", "*BOUNDARY_PRESCRIBED_MOTION_SET", "         1         3         2         7"},
       "field LCID (columns 31-40) = 7: a displacement curve (VAD 2) needs 2 points or more and "
       "d(0) = 0"},
      {{"*SET_SHELL_LIST", "         4", "         1"},
       "*SET_SHELL_LIST field ID1 (columns 1-10) = 1: shell 1 is not defined"},
      {{"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         4         2         1         3"},
       "field SSID (columns 1-10) = 4: shell set 4 is not defined (SSTYP 1"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.message);
    const std::string msg = read(testing::two_cubes_with(c.lines));
    EXPECT_NE(msg.find(c.message), std::string::npos) << msg;
  }
  // *MAT_RIGID: local constraints and codes out of range
  EXPECT_NE(read(rigid_upper({}, "      -1.0         1")).find("field CMO (columns 1-10) = -1.0"),
            std::string::npos);
  EXPECT_NE(read(rigid_upper({}, "       1.0         8")).find("field CON1 (columns 11-20) = 8"),
            std::string::npos);
}

}  // namespace
}  // namespace crashlink::deck
