// The twin deck (tests/data/decks/twin: fixed, long and free format across three files joined by
// *INCLUDE, with *PARAMETERs) read into the model in SI (solver/deck/model_from_deck.h); its
// comparison with the YAML twin is tests/integration/deck_twin_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

const std::string kTwin = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/twin/main.k";

TEST(DeckModel, TwinReadsInSI) {
  const DeckRead r = read_deck(kTwin, {"mm-t-s", {}});
  const model::Model& m = r.model;
  EXPECT_EQ(m.name, "deck_twin");
  EXPECT_EQ(m.nodes.count(), 12u + 9u + 4u + 8u + 8u + 6u);
  ASSERT_EQ(m.parts.size(), 6u);
  EXPECT_EQ(m.parts[0].name, "bar");
  EXPECT_EQ(m.parts[1].name, "plate");
  EXPECT_EQ(m.parts[3].name, "block2");
  EXPECT_EQ(m.parts[4].name, "tab");
  EXPECT_EQ(m.parts[5].name, "block");  // its *PART_INERTIA after the include
  EXPECT_EQ(m.parts[0].kind, model::ElementKind::Hex8);
  EXPECT_EQ(m.parts[1].kind, model::ElementKind::Shell4);
  EXPECT_EQ(m.parts[0].element_count(), 2u);
  EXPECT_EQ(m.parts[1].element_count(), 4u);
  EXPECT_DOUBLE_EQ(m.parts[1].thickness_m, 1.0e-3);      // &tplate = -(-0.5)*2 mm
  EXPECT_DOUBLE_EQ(m.parts[2].thickness_m, 0.5e-3);      // &tstrip = sqrt(0.25) mm
  EXPECT_DOUBLE_EQ(m.parts[2].thickness_of(0), 0.5e-3);  // *ELEMENT_SHELL_THICKNESS
  EXPECT_EQ(m.parts[1].through_thickness_points, 5);     // &nip
  EXPECT_EQ(m.parts[2].through_thickness_points, 3);
  EXPECT_DOUBLE_EQ(m.parts[0].hourglass_coefficient, 0.05);  // *HOURGLASS 1
  EXPECT_DOUBLE_EQ(m.parts[1].hourglass_coefficient, 0.08);  // *CONTROL_HOURGLASS
  // Node 2 of the long-format mesh: (10, 0, 0) mm.
  const int n2 = m.node_index(2);
  ASSERT_GE(n2, 0);
  EXPECT_DOUBLE_EQ(m.nodes.x0[3 * static_cast<std::size_t>(n2)], 0.01);
  // Materials in SI: steel from the parameters, *MAT_024's curve, *MAT_003's bilinear curve.
  const auto& steel = m.materials[static_cast<std::size_t>(m.parts[0].material)];
  EXPECT_EQ(steel.name, "steel");
  EXPECT_NEAR(steel.density_kg_m3, 7850.0, 1e-9);
  EXPECT_NEAR(steel.youngs_modulus_Pa, 2.1e11, 1.0);
  const auto& al = m.materials[static_cast<std::size_t>(m.parts[1].material)];
  EXPECT_EQ(al.kind, materials::MaterialKind::J2Plastic);
  ASSERT_EQ(al.hardening.eps_p.size(), 3u);
  EXPECT_NEAR(al.hardening.sigma_y_Pa[2], 3.0e8, 1e-3);
  const auto& k = m.materials[static_cast<std::size_t>(m.parts[2].material)];
  EXPECT_NEAR(k.hardening.slope(0.0), 2.0e11 * 1.0e9 / (2.0e11 - 1.0e9), 1.0);
  // The rigid block (with block2 merged into it) has its *PART_INERTIA's mass and velocity; the
  // nodal body 'cap' and the welds 40 (*CONSTRAINED_SPOTWELD_ID) and 41 (GENERALIZED) follow.
  ASSERT_EQ(m.rigid_bodies.size(), 6u);
  EXPECT_EQ(m.rigid_bodies[0].name, "block");
  EXPECT_EQ(m.rigid_bodies[0].parts.size(), 2u);
  EXPECT_DOUBLE_EQ(m.rigid_bodies[0].mass_kg, 10.0);
  EXPECT_DOUBLE_EQ(m.rigid_bodies[0].velocity_m_s[2], -5.0);
  EXPECT_EQ(m.rigid_bodies[0].fixed, model::kRx | model::kRy | model::kRz);
  EXPECT_EQ(m.rigid_bodies[1].name, "cap");  // _SPC: rotations held
  EXPECT_EQ(m.rigid_bodies[1].fixed, model::kRx | model::kRy | model::kRz);
  EXPECT_EQ(m.rigid_bodies[2].name, "nodal_rigid_body_300");
  EXPECT_EQ(m.rigid_bodies[3].name, "nodal_rigid_body_200");  // _INERTIA
  EXPECT_DOUBLE_EQ(m.rigid_bodies[3].mass_kg, 2.0);
  EXPECT_NEAR(m.rigid_bodies[3].inertia_kg_m2[2][2], 1.0e-4, 1e-18);
  EXPECT_DOUBLE_EQ(m.rigid_bodies[3].angular_velocity_rad_s[2], 2.0);
  EXPECT_EQ(m.rigid_bodies[4].name, "spotweld_40");
  EXPECT_EQ(m.rigid_bodies[5].name, "spotweld_41");
  EXPECT_DOUBLE_EQ(m.rigid_bodies[5].failure.normal_N, 1200.0);
  EXPECT_DOUBLE_EQ(m.rigid_bodies[5].failure.time_s, 1000.0);
  ASSERT_EQ(m.initial_velocities.size(), 3u);
  EXPECT_DOUBLE_EQ(m.initial_velocities[2].velocity_m_s[1], 1.0);  // local x = global y
  // Constraints: the bar's end (4 nodes, all dofs), the strip in z (4 nodes), node 107 in y.
  EXPECT_EQ(std::count(m.fixed.begin(), m.fixed.end(), 63), 4);
  EXPECT_EQ(std::count(m.fixed.begin(), m.fixed.end(), model::kUz), 4);
  EXPECT_EQ(std::count(m.fixed.begin(), m.fixed.end(), model::kUy), 1);
  EXPECT_DOUBLE_EQ(m.controls.end_time_s, 1.0e-4);
  EXPECT_DOUBLE_EQ(m.controls.dt_scale, 0.8);
  EXPECT_DOUBLE_EQ(m.controls.history_interval_s, 1.0e-6);  // *DATABASE_GLSTAT DT
  EXPECT_DOUBLE_EQ(m.controls.field_interval_s, 2.0e-5);    // *DATABASE_BINARY_D3PLOT DT
  EXPECT_EQ(m.contacts.size(), 6u);
  EXPECT_EQ(m.rigid_walls.size(), 6u);
  // What the user is told: the blank SHRF.
  std::string all;
  for (const auto& s : r.messages) all += s + "\n";
  EXPECT_NE(all.find(": *SECTION_SHELL 3: SHRF blank (LS-DYNA reads 1.0)"), std::string::npos)
      << all;
}

// *SECTION_SHELL T1-T4 unequal: each shell takes their mean (a triangle T1-T3's), as
// *ELEMENT_SHELL_THICKNESS would give it, and the reader says so.
TEST(DeckModel, SectionCornerThicknessesGiveTheirMean) {
  testing::DeckFolder dir;
  const std::string text = R"(*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
       3             1.0             1.0             0.0
       4             0.0             1.0             0.0
       5             2.0             0.0             0.0
*ELEMENT_SHELL
       1       1       1       2       3       4
       2       1       2       5       3       3
*PART
sheet
         1         1         1
*SECTION_SHELL
         1         2  0.833333         3
       1.0       2.0       3.0       6.0
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*CONTROL_TERMINATION
    1.0e-5
*END
)";
  const DeckRead r = read_deck(dir.write("s.k", text), {"mm-t-s", {}});
  const auto& p = r.model.parts[0];
  ASSERT_EQ(p.element_thickness_m.size(), 2u);
  EXPECT_DOUBLE_EQ(p.thickness_of(0), 3.0e-3);  // (1 + 2 + 3 + 6) / 4 mm
  EXPECT_DOUBLE_EQ(p.thickness_of(1), 2.0e-3);  // the triangle: (1 + 2 + 3) / 3 mm
  std::string all;
  for (const auto& m : r.messages) all += m + "\n";
  EXPECT_NE(all.find("*SECTION_SHELL 1: T1-T4 unequal (1, 2, 3, 6): each shell takes their mean"),
            std::string::npos)
      << all;
}

TEST(DeckModel, UnitSystemsConvertToSI) {
  const auto* u = find_unit_system("in-lbf-s");
  ASSERT_NE(u, nullptr);
  EXPECT_NEAR(u->stress_Pa(), 6894.757, 1e-3);  // psi
  EXPECT_NEAR(u->force_N(), 4.4482216152605, 1e-12);
  EXPECT_NEAR(u->density_kg_m3() * 2.59e-4, 2768.0, 1.0);  // the beer can's aluminium
  const auto* g = find_unit_system("cm-g-us");
  ASSERT_NE(g, nullptr);
  EXPECT_NEAR(g->stress_Pa(), 1e11, 1e-3);  // Mbar
  EXPECT_NEAR(g->velocity_m_s(), 1e4, 1e-9);
  EXPECT_NEAR(find_unit_system("mm-kg-ms")->stress_Pa(), 1e9, 1e-3);  // GPa
  EXPECT_NEAR(find_unit_system("mm-g-ms")->stress_Pa(), 1e6, 1e-6);   // MPa
  EXPECT_EQ(find_unit_system("mm-t-ms"), nullptr);
}

TEST(DeckModel, TriangleAsN3EqualN4) {
  testing::DeckFolder dir;
  const std::string deck = dir.write(
      "tri.k",
      "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n*ELEMENT_SHELL\n1,1,1,2,3,3\n*PART\ntri\n"
      "1,1,1\n*SECTION_SHELL\n1,2,,3\n0.1\n*MAT_ELASTIC\n1,7.85e-9,2.1e5,0.3\n"
      "*CONTROL_TERMINATION\n1e-4\n");
  const auto m = read_deck(deck, {"mm-t-s", {}}).model;
  ASSERT_EQ(m.parts.size(), 1u);
  const auto& c = m.parts[0].connectivity;
  EXPECT_EQ(c[2], c[3]);
}

}  // namespace
}  // namespace crashlink::deck
