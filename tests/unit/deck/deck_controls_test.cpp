// *HOURGLASS / *CONTROL_HOURGLASS (per-part and model hourglass coefficients),
// *CONTROL_BULK_VISCOSITY and *LOAD_BODY_X/Y/Z read into the model (docs/decks.md "Keywords"),
// and their mistakes and those of *RIGIDWALL_PLANAR (its run: integration/rigid_wall_test.cpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

class DeckControls : public testing::DeckLinesTest {};

/// The two cubes with part 2's HGID set to `hgid` (its card is line 27 of the deck, index 26).
std::vector<std::string> with_hgid(const char* hgid) {
  auto d = testing::two_cubes();
  d[26] = std::string("         2         1         1         0") + hgid;
  return d;
}

TEST_F(DeckControls, HourglassBulkViscosityAndGravity) {
  auto d = with_hgid("         7");
  d.insert(d.end(),
           {"*HOURGLASS", "         7         4      0.05", "*CONTROL_HOURGLASS",
            "         5      0.08", "*CONTROL_BULK_VISCOSITY", "       1.2      0.05        -2",
            // gravity along -z: a base acceleration of +9810 mm/s^2 (a constant curve)
            "*DEFINE_CURVE", "        11", "                 0.0              9810.0",
            "                 1.0              9810.0", "*LOAD_BODY_Z", "        11       1.0"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  const auto& m = r.model;
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_DOUBLE_EQ(m.parts[0].hourglass_coefficient, 0.08);  // *CONTROL_HOURGLASS
  EXPECT_DOUBLE_EQ(m.parts[1].hourglass_coefficient, 0.05);  // its own *HOURGLASS
  EXPECT_DOUBLE_EQ(m.controls.bulk_q_quadratic, 1.2);
  EXPECT_DOUBLE_EQ(m.controls.bulk_q_linear, 0.05);
  EXPECT_TRUE(m.controls.shell_bulk_viscosity);
  EXPECT_DOUBLE_EQ(m.controls.gravity_m_s2[0], 0.0);
  EXPECT_DOUBLE_EQ(m.controls.gravity_m_s2[2], -9.81);
  // Without those keywords: crashlink's (and LS-DYNA's) defaults.
  ASSERT_EQ(read(testing::two_cubes(), &r), "");
  EXPECT_DOUBLE_EQ(r.model.parts[0].hourglass_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(r.model.controls.bulk_q_quadratic, 1.5);
  EXPECT_DOUBLE_EQ(r.model.controls.bulk_q_linear, 0.06);
  EXPECT_FALSE(r.model.controls.shell_bulk_viscosity);
}

TEST_F(DeckControls, ViscousHourglassIsReadAsTheStiffnessFormWithANote) {
  auto d = testing::two_cubes();
  d.insert(d.end(), {"*CONTROL_HOURGLASS", "         1      0.05"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  EXPECT_DOUBLE_EQ(r.model.parts[0].hourglass_coefficient, 0.05);
  bool noted = false;
  for (const auto& s : r.messages)
    noted = noted || s.find(
                         "*CONTROL_HOURGLASS IHQ 1: LS-DYNA's viscous hourglass control; "
                         "crashlink computes the stiffness form (IHQ 4)") != std::string::npos;
  EXPECT_TRUE(noted);
}

/// The two cubes with `mat` (lines) in place of their *MAT_ELASTIC (lines 30-31, index 29-30).
std::vector<std::string> with_material(std::vector<std::string> mat) {
  auto d = testing::two_cubes();
  d.erase(d.begin() + 29, d.begin() + 31);
  d.insert(d.begin() + 29, mat.begin(), mat.end());
  return d;
}

TEST_F(DeckControls, CowperSymondsRatesReadIntoTheMaterial) {
  DeckRead r;
  // *MAT_003 SRC, SRP (mm-t-s: C in 1/s)
  ASSERT_EQ(read(with_material({"*MAT_PLASTIC_KINEMATIC",
                                "         1   7.85e-9  210000.0       0.3     250.0     100.0"
                                "       1.0",
                                "      40.4       5.0"}),
                 &r),
            "");
  ASSERT_EQ(r.model.materials.size(), 1u);
  EXPECT_DOUBLE_EQ(r.model.materials[0].rate_c_per_s, 40.4);
  EXPECT_DOUBLE_EQ(r.model.materials[0].rate_p, 5.0);
  EXPECT_TRUE(r.model.materials[0].rate_dependent());
  // *MAT_024 C, P with VP -1; blank C: no rate effect
  ASSERT_EQ(read(with_material({"*MAT_PIECEWISE_LINEAR_PLASTICITY",
                                "         1   7.85e-9  210000.0       0.3     250.0     100.0",
                                "    6844.0     3.91                            -1"}),
                 &r),
            "");
  EXPECT_DOUBLE_EQ(r.model.materials[0].rate_c_per_s, 6844.0);
  EXPECT_DOUBLE_EQ(r.model.materials[0].rate_p, 3.91);
  ASSERT_EQ(
      read(with_material({"*MAT_PIECEWISE_LINEAR_PLASTICITY",
                          "         1   7.85e-9  210000.0       0.3     250.0     100.0", ""}),
           &r),
      "");
  EXPECT_FALSE(r.model.materials[0].rate_dependent());
  // VP without a rate coefficient changes nothing: read as written
  ASSERT_EQ(read(with_material({"*MAT_PIECEWISE_LINEAR_PLASTICITY",
                                "         1   7.85e-9  210000.0       0.3     250.0     100.0",
                                "                                                 1"}),
                 &r),
            "");
  EXPECT_FALSE(r.model.materials[0].rate_dependent());
}

// C is 1/time: 0.0404 per ms in mm-kg-ms is 40.4 1/s.
TEST_F(DeckControls, RateCoefficientIsConvertedFromTheDecksTime) {
  auto d = with_material({"*MAT_PLASTIC_KINEMATIC",
                          "         1   7.85e-6     210.0       0.3     0.250     0.100       1.0",
                          "    0.0404       5.0"});
  d.push_back("*END");
  std::string text;
  for (const auto& line : d) text += line + "\n";
  const auto path = dir_.write("ms.k", text);
  const auto m = read_deck(path, {"mm-kg-ms", {}}).model;
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_NEAR(m.materials[0].rate_c_per_s, 40.4, 1e-12);
  EXPECT_NEAR(m.materials[0].hardening.sigma_y_Pa[0], 250e6, 1e-3);
}

// *RIGIDWALL_PLANAR_MOVING (either order with _ID): the mass and velocity in SI.
// Two walls with one heading: the second gets its number (result.h5 needs distinct names).
TEST_F(DeckControls, WallHeadingsAreMadeUnique) {
  DeckRead r;
  const std::vector<std::string> wall = {
      "*RIGIDWALL_PLANAR_ID", "         1floor", "         0",
      "       0.0       0.0      -1.0       0.0       0.0       1.0"};
  auto lines = wall;
  lines.insert(lines.end(), wall.begin(), wall.end());
  ASSERT_EQ(read(testing::two_cubes_with(lines), &r), "");
  ASSERT_EQ(r.model.rigid_walls.size(), 2u);
  EXPECT_EQ(r.model.rigid_walls[0].name, "floor");
  EXPECT_EQ(r.model.rigid_walls[1].name, "floor (2)");
}

TEST_F(DeckControls, MovingWallReadsItsMassAndVelocity) {
  DeckRead r;
  ASSERT_EQ(
      read(testing::two_cubes_with({"*RIGIDWALL_PLANAR_MOVING_ID", "         3ram", "         0",
                                    "       0.0       0.0      -1.0       0.0       0.0       1.0",
                                    "     0.250    5000.0"}),
           &r),
      "");
  ASSERT_EQ(r.model.rigid_walls.size(), 1u);
  EXPECT_EQ(r.model.rigid_walls[0].name, "ram");
  EXPECT_DOUBLE_EQ(r.model.rigid_walls[0].mass_kg, 250.0);  // t
  EXPECT_DOUBLE_EQ(r.model.rigid_walls[0].velocity_m_s, 5.0);
  // _FINITE without its card
  EXPECT_EQ(read(testing::two_cubes_with(
                {"*RIGIDWALL_PLANAR_FINITE", "         0",
                 "       0.0       0.0      -1.0       0.0       0.0       1.0"})),
            "c.k:34: *RIGIDWALL_PLANAR_FINITE: its cards are missing (the next keyword or the end "
            "of the file follows); fix: add them or remove the keyword");
  EXPECT_NE(read(testing::two_cubes_with(
                     {"*RIGIDWALL_PLANAR_ORTHO", "         0",
                      "       0.0       0.0      -1.0       0.0       0.0       1.0"}))
                .find("c.k:34: *RIGIDWALL_PLANAR_ORTHO: not supported; fix: remove it, or pass "
                      "--ignore RIGIDWALL_PLANAR_ORTHO"),
            std::string::npos);
}

// *BOUNDARY_PRESCRIBED_MOTION_NODE/_SET and *LOAD_NODE_POINT/_SET onto the model's prescribed
// velocities and nodal loads, the curve in SI (SFA, OFFA on time, SF x SFO, OFFO on the value).
TEST_F(DeckControls, PrescribedMotionAndNodalLoads) {
  DeckRead r;
  ASSERT_EQ(
      read(testing::two_cubes_with(
               {"*DEFINE_CURVE", "         7       0.0       2.0       3.0       0.0       1.0",
                "                 0.0                 0.0",
                "                 1.0              1000.0", "*SET_NODE_LIST", "         4",
                "         5         6         7         8", "*BOUNDARY_PRESCRIBED_MOTION_SET",
                "         4         3         0         7       0.5",
                "*BOUNDARY_PRESCRIBED_MOTION_NODE", "         1         6         0         7",
                "*LOAD_NODE_POINT", "        16         1         7       2.0", "*LOAD_NODE_SET",
                "         4         2         7"}),
           &r),
      "");
  const auto& m = r.model;
  ASSERT_EQ(m.prescribed_velocities.size(), 2u);
  ASSERT_EQ(m.loads.size(), 2u);
  const auto& pv = m.prescribed_velocities[0];
  EXPECT_EQ(pv.dof, 2);  // DOF 3: z
  EXPECT_EQ(pv.nodes.size(), 4u);
  // SFA 2, SFO 3, OFFO 1: abscissae 2 x (0, 1) s; ordinates SF 0.5 x 3 x ((0, 1000) + 1) mm/s
  ASSERT_EQ(pv.velocity.t_s.size(), 2u);
  EXPECT_DOUBLE_EQ(pv.velocity.t_s[1], 2.0);
  EXPECT_DOUBLE_EQ(pv.velocity.value[0], 0.5 * 3.0 * 1.0 * 1e-3);
  EXPECT_DOUBLE_EQ(pv.velocity.value[1], 0.5 * 3.0 * 1001.0 * 1e-3);
  EXPECT_EQ(m.prescribed_velocities[1].dof, 4);                            // DOF 6: about y
  EXPECT_DOUBLE_EQ(m.prescribed_velocities[1].velocity.value[1], 3003.0);  // rad/s
  EXPECT_EQ(m.loads[0].dof, 0);
  EXPECT_EQ(m.nodes.id[static_cast<std::size_t>(m.loads[0].nodes[0])], 16);
  EXPECT_DOUBLE_EQ(m.loads[0].force.value[1], 6006.0);  // N: 2 x 3 x 1001 (t mm/s^2)
  EXPECT_EQ(m.loads[1].dof, 1);
  EXPECT_EQ(m.loads[1].nodes.size(), 4u);
}

// *PART_INERTIA on a rigid part: the body's mass, centre, inertia tensor and velocities in SI;
// on a deformable part it is refused.
TEST_F(DeckControls, PartInertiaGivesTheRigidBody) {
  auto d = testing::two_cubes();
  // part 2 (lines 25-27, index 24-26) with its inertia, on a rigid material 2
  d.erase(d.begin() + 24, d.begin() + 27);
  d.insert(d.begin() + 24, {"*PART_INERTIA", "upper", "         2         1         2",
                            "       0.5       0.5       2.0     0.004",
                            "      10.0       1.0       0.0      20.0       0.0      30.0",
                            "       0.0       0.0   -5000.0       0.0       0.0     100.0"});
  d.insert(d.end(), {"*MAT_RIGID", "         2   7.85e-9  210000.0       0.3"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  ASSERT_EQ(r.model.rigid_bodies.size(), 1u);
  const auto& b = r.model.rigid_bodies[0];
  EXPECT_EQ(b.name, "upper");
  EXPECT_DOUBLE_EQ(b.mass_kg, 4.0);  // 0.004 t
  ASSERT_TRUE(b.centre_given);
  EXPECT_DOUBLE_EQ(b.centre_m[2], 2.0e-3);
  ASSERT_TRUE(b.inertia_given);
  EXPECT_DOUBLE_EQ(b.inertia_kg_m2[0][0], 10.0e-3);  // t mm^2 = 1e-3 kg m^2
  EXPECT_DOUBLE_EQ(b.inertia_kg_m2[0][1], 1.0e-3);
  EXPECT_DOUBLE_EQ(b.inertia_kg_m2[1][0], 1.0e-3);
  EXPECT_DOUBLE_EQ(b.inertia_kg_m2[2][2], 30.0e-3);
  EXPECT_DOUBLE_EQ(b.velocity_m_s[2], -5.0);
  EXPECT_DOUBLE_EQ(b.angular_velocity_rad_s[2], 100.0);
  // *INITIAL_VELOCITY_GENERATION on the part: IRIGID 0 (default) keeps the inertia card's
  // velocity, with a note; 1 replaces it; the plain *INITIAL_VELOCITY keeps it too
  for (const char* irigid : {"         0", "         1"}) {
    auto g = d;
    g.insert(g.end(), {"*INITIAL_VELOCITY_GENERATION", "         2         2       0.0    7000.0",
                       std::string(70, ' ') + irigid});
    ASSERT_EQ(read(g, &r), "");
    EXPECT_DOUBLE_EQ(r.model.rigid_bodies[0].velocity_m_s[0], irigid[9] == '1' ? 7.0 : 0.0);
    EXPECT_DOUBLE_EQ(r.model.rigid_bodies[0].velocity_m_s[2], irigid[9] == '1' ? 0.0 : -5.0);
  }
  // the same on the deformable part 1: refused at TM
  auto e = testing::two_cubes();
  e.erase(e.begin() + 21, e.begin() + 24);
  e.insert(e.begin() + 21, {"*PART_INERTIA", "lower", "         1         1         1",
                            "       0.5       0.5       0.5     0.004", "", ""});
  EXPECT_EQ(read(e),
            "c.k:25: *PART_INERTIA field TM (columns 31-40) = 0.004: crashlink reads "
            "*PART_INERTIA on rigid parts (*MAT_RIGID) only: a deformable part's mass comes from "
            "its elements; fix: write *PART, or give the part a *MAT_RIGID material");
}

// *INITIAL_VELOCITY: NSID 0 is every node, else the node set; ICID turns the velocity.
TEST_F(DeckControls, PlainInitialVelocity) {
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes_with(
                     {"*INITIAL_VELOCITY", "         0", "    1000.0       0.0   -2000.0"}),
                 &r),
            "");
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  EXPECT_EQ(r.model.initial_velocities[0].nodes.size(), 16u);
  EXPECT_DOUBLE_EQ(r.model.initial_velocities[0].velocity_m_s[0], 1.0);
  EXPECT_DOUBLE_EQ(r.model.initial_velocities[0].velocity_m_s[2], -2.0);
  ASSERT_EQ(
      read(testing::two_cubes_with({"*SET_NODE_LIST", "         3", "         1         2",
                                    "*INITIAL_VELOCITY", "         3", "       0.0    3000.0"}),
           &r),
      "");
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  EXPECT_EQ(r.model.initial_velocities[0].nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(r.model.initial_velocities[0].velocity_m_s[1], 3.0);
  // a rigid body with nodes in the set takes the velocity (its nodes follow it); a blank line
  // between records is skipped
  auto d = testing::two_cubes_with(
      {"*INITIAL_VELOCITY", "         0", "    1000.0       0.0   -2000.0", ""});
  d[26] = "         2         1         2";
  d.insert(d.end(), {"*MAT_RIGID", "         2   7.85e-9  210000.0       0.3"});
  ASSERT_EQ(read(d, &r), "");
  ASSERT_EQ(r.model.rigid_bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(r.model.rigid_bodies[0].velocity_m_s[0], 1.0);
  EXPECT_DOUBLE_EQ(r.model.rigid_bodies[0].velocity_m_s[2], -2.0);
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  EXPECT_EQ(r.model.initial_velocities[0].nodes.size(), 8u);  // the deformable cube's
  // a generated range far wider than the ids there are (1 to 1e9): its defined ids
  ASSERT_EQ(read(testing::two_cubes_with({"*SET_NODE_LIST_GENERATE", "         5",
                                          "         91000000000", "*INITIAL_VELOCITY", "         5",
                                          "       0.0       0.0    1000.0"}),
                 &r),
            "");
  ASSERT_EQ(r.model.initial_velocities.size(), 1u);
  EXPECT_EQ(r.model.initial_velocities[0].nodes.size(), 8u);  // nodes 9-16
  EXPECT_EQ(read(testing::two_cubes_with({"*INITIAL_VELOCITY", "         0"})),
            "c.k:34: *INITIAL_VELOCITY: its cards are missing (the next keyword or the end of the "
            "file follows); fix: add them or remove the keyword");
}

// *CONTROL_CONTACT SLSFAC scales every contact's penalty; *CONTROL_SHELL THEORY 2 and ISTUPD are
// read (LS-DYNA's ISTUPD 0 noted: crashlink's shells thin); *CONTROL_ENERGY is without effect.
TEST_F(DeckControls, ContactShellAndEnergyControls) {
  const std::vector<std::string> contact = {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
                                            "         1         2         3         3", "",
                                            "       2.0       2.0"};
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes_with(contact), &r), "");
  ASSERT_EQ(r.model.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(r.model.contacts[0].penalty_scale, 0.2);  // 0.1 x SFS 2
  auto with_control = contact;
  with_control.insert(with_control.end(),
                      {"*CONTROL_CONTACT", "      0.05                             1",
                       "*CONTROL_SHELL", "                                       1         2",
                       "*CONTROL_ENERGY", "         2         2"});
  ASSERT_EQ(read(testing::two_cubes_with(with_control), &r), "");
  EXPECT_DOUBLE_EQ(r.model.contacts[0].penalty_scale, 0.1);  // 0.05 x SFS 2
  std::string all;
  for (const auto& m : r.messages) all += m + "\n";
  EXPECT_NE(all.find("*CONTROL_CONTACT SHLTHK not read"), std::string::npos) << all;
  EXPECT_NE(all.find("accepted without effect (crashlink writes its own output): "
                     "*CONTROL_ENERGY"),
            std::string::npos)
      << all;
  EXPECT_EQ(read(testing::two_cubes_with(
                {"*CONTROL_SHELL", "                                       1         1"})),
            "c.k:35: *CONTROL_SHELL field THEORY (columns 41-50) = 1: crashlink computes the "
            "Belytschko-Tsay shell (THEORY 2) only; fix: write 2");
}

TEST_F(DeckControls, MistakesNameTheirField) {
  struct Mistake {
    const char* what;
    std::vector<std::string> deck;
    std::string message;
  };
  const std::string k003 = "         1   7.85e-9  210000.0       0.3     250.0     100.0       1.0";
  const std::string k024 = "         1   7.85e-9  210000.0       0.3     250.0     100.0";
  const Mistake mistakes[] = {
      {"a shell element without its thickness card",
       testing::two_cubes_with({"*NODE", "      41             0.0             0.0             5.0",
                                "      42             1.0             0.0             5.0",
                                "      43             1.0             1.0             5.0",
                                "*ELEMENT_SHELL_THICKNESS",
                                "       9       1      41      42      43      43"}),
       "c.k:39: *ELEMENT_SHELL_THICKNESS: an element's thickness card (THIC1-THIC4) is missing "
       "after its node card; fix: add it"},
      {"a negative shell thickness",
       testing::two_cubes_with({"*ELEMENT_SHELL_THICKNESS",
                                "       9       1       1       2       3       3",
                                "            -1.0"}),
       "c.k:36: *ELEMENT_SHELL_THICKNESS field THIC1 (columns 1-16) = -1.0: must be >= 0 (0: the "
       "section's thickness); fix: write it"},
      {"motion along a vector",
       testing::two_cubes_with(
           {"*BOUNDARY_PRESCRIBED_MOTION_NODE", "         1         4         0         7"}),
       "c.k:35: *BOUNDARY_PRESCRIBED_MOTION_NODE field DOF (columns 11-20) = 4: crashlink "
       "prescribes x, y, z (DOF 1, 2, 3) or rotations about them (5, 6, 7); motion along a "
       "vector (4, 8), in a local system (negative) or of all translations (9-12) is not "
       "computed; fix: one card per global dof"},
      {"an acceleration curve",
       testing::two_cubes_with(
           {"*BOUNDARY_PRESCRIBED_MOTION_NODE", "         1         3         1         7"}),
       "c.k:35: *BOUNDARY_PRESCRIBED_MOTION_NODE field VAD (columns 21-30) = 1: crashlink "
       "prescribes a velocity (VAD 0) or a displacement (2, as the velocity of each segment's "
       "slope); an acceleration (1) curve is not converted; fix: give the velocity (VAD 0) or "
       "displacement (VAD 2) curve"},
      {"an undefined curve",
       testing::two_cubes_with({"*LOAD_NODE_POINT", "         1         3        99"}),
       "c.k:35: *LOAD_NODE_POINT field LCID (columns 21-30) = 99: curve 99 is not defined; fix: "
       "add *DEFINE_CURVE 99"},
      {"a moment", testing::two_cubes_with({"*LOAD_NODE_POINT", "         1         5         7"}),
       "c.k:35: *LOAD_NODE_POINT field DOF (columns 11-20) = 5: crashlink loads a node along x, "
       "y or z (DOF 1, 2, 3); moments, follower forces and loads along a vector are not "
       "computed; fix: write 1, 2 or 3"},
      {"negative rate coefficient",
       with_material({"*MAT_PLASTIC_KINEMATIC", k003, "     -40.4       5.0"}),
       "c.k:32: *MAT_PLASTIC_KINEMATIC field SRC (columns 1-10) = -40.4: must be >= 0 (0: no "
       "strain-rate effect); fix: write SRC in 1/time of the deck's units (mild steel: 40.4 1/s)"},
      {"rate coefficient without exponent",
       with_material({"*MAT_PLASTIC_KINEMATIC", k003, "      40.4"}),
       "c.k:32: *MAT_PLASTIC_KINEMATIC field SRP (columns 11-20) = (blank): must be > 0 when SRC "
       "is given; fix: write SRP (mild steel: 5)"},
      {"viscoplastic 003",
       with_material({"*MAT_PLASTIC_KINEMATIC", k003, "      40.4       5.0                   1"}),
       "c.k:32: *MAT_PLASTIC_KINEMATIC field VP (columns 31-40) = 1: the viscoplastic rate "
       "formulation (VP 1) is not computed; fix: write VP 0 (the yield stress scaled by the "
       "Cowper-Symonds factor)"},
      {"viscoplastic 024",
       with_material({"*MAT_PIECEWISE_LINEAR_PLASTICITY", k024,
                      "      40.4       5.0                             1"}),
       "c.k:32: *MAT_PIECEWISE_LINEAR_PLASTICITY field VP (columns 41-50) = 1: the viscoplastic "
       "rate formulation (VP 1) and the tables of VP 3 are not computed; fix: write VP 0 or -1 "
       "(the yield stress scaled by the Cowper-Symonds factor)"},
      {"assumed-strain hourglass", testing::two_cubes_with({"*CONTROL_HOURGLASS", "         6"}),
       "c.k:35: *CONTROL_HOURGLASS field IHQ (columns 1-10) = 6: crashlink computes the "
       "stiffness hourglass control (IHQ 4 and 5: Flanagan-Belytschko for hexahedra, "
       "Belytschko-Tsay for shells); the viscous forms 2 and 3 and the assumed-strain ones (6 "
       "and up) are not computed; fix: write IHQ 4"},
      {"undefined HGID", with_hgid("         3"),
       "c.k:27: *PART field HGID (columns 41-50) = 3: *HOURGLASS 3 is not defined; fix: add it "
       "or leave HGID blank"},
      {"coefficient too large",
       testing::two_cubes_with({"*HOURGLASS", "         3         4       0.5"}),
       "c.k:35: *HOURGLASS field QM (columns 21-30) = 0.5: must lie in (0, 0.3]; fix: write "
       "0.05-0.1 (stiffness form)"},
      {"bulk viscosity per part",
       testing::two_cubes_with(
           {"*HOURGLASS", "         3         4      0.05         0       1.5"}),
       "c.k:35: *HOURGLASS field Q1 (columns 41-50) = 1.5: a bulk viscosity per part (Q1, Q2) is "
       "not computed; fix: leave them blank and set the model's in *CONTROL_BULK_VISCOSITY"},
      {"a body load that changes",
       testing::two_cubes_with({"*DEFINE_CURVE", "        11", "0.0, 0.0", "1.0, 9810.0",
                                "*LOAD_BODY_Y", "        11"}),
       "c.k:39: *LOAD_BODY_Y field LCID (columns 1-10) = 11: curve 11 changes in time "
       "(*DEFINE_CURVE at c.k:35): crashlink's body acceleration is constant; fix: a curve with "
       "one value"},
      {"bulk viscosity type",
       testing::two_cubes_with({"*CONTROL_BULK_VISCOSITY", "       1.5      0.06         2"}),
       "c.k:35: *CONTROL_BULK_VISCOSITY field TYPE (columns 21-30) = 2: crashlink computes the "
       "standard bulk viscosity of solids (TYPE 1) and, with TYPE -2, of shells too; fix: write "
       "1 or -2"},
      {"friction on a rigid wall",
       testing::two_cubes_with({"*RIGIDWALL_PLANAR", "         0",
                                "       0.0       0.0       0.0       0.0       0.0       1.0"
                                "       0.3"}),
       "c.k:36: *RIGIDWALL_PLANAR field FRIC (columns 61-70) = 0.3: friction on the wall (FRIC) "
       "is not computed: the wall is frictionless; fix: write 0"},
      {"a rigid wall without a normal",
       testing::two_cubes_with({"*RIGIDWALL_PLANAR", "         0",
                                "       0.0       0.0       0.0       0.0       0.0       0.0"}),
       "c.k:36: *RIGIDWALL_PLANAR field XH (columns 31-40) = 0.0: the head point is the tail "
       "point: the wall has no normal; fix: put the head on the side of the nodes the wall "
       "stops"},
      {"a rigid wall without its card 2",
       testing::two_cubes_with({"*RIGIDWALL_PLANAR", "         0"}),
       "c.k:34: *RIGIDWALL_PLANAR: its cards are missing (the next keyword or the end of the file "
       "follows); fix: add them or remove the keyword"},
      {"a prescribed motion without its card",
       testing::two_cubes_with({"*BOUNDARY_PRESCRIBED_MOTION_NODE", "*END"}),
       "c.k:34: *BOUNDARY_PRESCRIBED_MOTION_NODE: its cards are missing (the next keyword or "
       "the end of the file follows); fix: add them or remove the keyword"},
      {"a moving wall without its mass",
       testing::two_cubes_with({"*RIGIDWALL_PLANAR_MOVING", "         0",
                                "       0.0       0.0      -1.0       0.0       0.0       1.0",
                                "          1000.0"}),
       "c.k:37: *RIGIDWALL_PLANAR_MOVING field MASS (columns 1-10) = (blank): a moving wall "
       "needs its mass (> 0); fix: write it in the deck's mass unit"},
      {"a moving wall without its card 3",
       testing::two_cubes_with({"*RIGIDWALL_PLANAR_ID_MOVING", "         3ram", "         0",
                                "       0.0       0.0      -1.0       0.0       0.0       1.0"}),
       "c.k:34: *RIGIDWALL_PLANAR_ID_MOVING: its cards are missing (the next keyword or the end "
       "of the file follows); fix: add them or remove the keyword"},
  };
  for (const auto& k : mistakes) {
    SCOPED_TRACE(k.what);
    EXPECT_EQ(read(k.deck), k.message);
  }
}

}  // namespace
}  // namespace crashlink::deck
