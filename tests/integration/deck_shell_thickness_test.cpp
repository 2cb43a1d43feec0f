// *ELEMENT_SHELL_THICKNESS: a shell strip clamped at one end, its free half 2 mm thick and the
// rest 1 mm, set up twice: as two parts with their sections' thicknesses, and as one part whose
// free half's elements carry THIC1-THIC4 = 2 mm. The two runs (mass, stiffness, contact
// thickness all from the element's thickness) give the same motion to round-off.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "solver/deck/model_from_deck.h"
#include "solver/integration/solver.h"
#include "tests/integration/run_helpers.h"

namespace crashlink {
namespace {

constexpr int kNx = 8, kNy = 2;  // 10 mm shells, 80 x 20 mm

/// The strip's deck: `per_element` true: one part (t 1 mm) with *ELEMENT_SHELL_THICKNESS 2 mm
/// on the elements of x > 40 mm; false: those elements in a second part with a 2 mm section.
std::string strip_deck(bool per_element) {
  std::string s = "*KEYWORD\n*NODE\n";
  char line[128];
  for (int j = 0; j <= kNy; ++j)
    for (int i = 0; i <= kNx; ++i) {
      std::snprintf(line, sizeof line, "%8d%16.6f%16.6f%16.6f\n", 1 + j * (kNx + 1) + i, 10.0 * i,
                    10.0 * j, 0.0);
      s += line;
    }
  std::string plain = "*ELEMENT_SHELL\n", thick = "*ELEMENT_SHELL_THICKNESS\n";
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const int a = 1 + j * (kNx + 1) + i, e = 1 + j * kNx + i;
      const bool free_half = i >= kNx / 2;
      std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d\n", e, free_half && !per_element ? 2 : 1,
                    a, a + 1, a + kNx + 2, a + kNx + 1);
      if (free_half && per_element) {
        thick += line;
        thick += "             2.0             2.0             2.0             2.0\n";
      } else {
        plain += line;
      }
    }
  s += plain;
  if (per_element) s += thick;
  s += "*PART\nstrip\n         1         1         1\n";
  if (!per_element) s += "*PART\nthick\n         2         2         1\n";
  s += "*SECTION_SHELL\n         1         2    0.8333         5\n       1.0       1.0       1.0"
       "       1.0\n";
  if (!per_element)
    s += "*SECTION_SHELL\n         2         2    0.8333         5\n       2.0       2.0       2.0"
         "       2.0\n";
  s += "*MAT_PLASTIC_KINEMATIC\n         1   7.85e-9  210000.0       0.3     250.0     500.0"
       "       1.0\n"
       "*SET_NODE_GENERAL\n         1\nBOX                1\n"
       "*DEFINE_BOX\n         1      -0.1       0.1    -100.0     100.0    -100.0     100.0\n"
       "*BOUNDARY_SPC_SET\n         1         0         1         1         1         1         1"
       "         1\n"
       "*INITIAL_VELOCITY\n         0\n       0.0       0.0    5000.0\n"
       "*CONTROL_TERMINATION\n    5.0E-4\n*END\n";
  return s;
}

model::Model read_strip(bool per_element) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_shell_thickness_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = (dir / (per_element ? "a.k" : "b.k")).string();
  std::ofstream(path) << strip_deck(per_element);
  model::Model m = deck::read_deck(path, {"mm-t-s", {}}).model;
  std::filesystem::remove_all(dir);
  return m;
}

TEST(DeckShellThickness, PerElementThicknessEqualsTwoSections) {
  const model::Model a = read_strip(true), b = read_strip(false);
  ASSERT_EQ(a.parts.size(), 1u);
  ASSERT_EQ(b.parts.size(), 2u);
  ASSERT_EQ(a.parts[0].element_thickness_m.size(), 16u);
  EXPECT_DOUBLE_EQ(a.parts[0].thickness_of(0), 1e-3);
  EXPECT_DOUBLE_EQ(a.parts[0].thickness_of(15), 2e-3);
  integration::Solver sa(a), sb(b);
  testing::run(sa, [](const integration::Solver&) {});
  testing::run(sb, [](const integration::Solver&) {});
  EXPECT_NEAR(sa.total_mass_kg(), sb.total_mass_kg(), 1e-15);
  // same node numbering in both decks: compare the tip's motion and every node's
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < sa.displacement().size(); ++k) {
    worst = std::max(worst, std::abs(sa.displacement()[k] - sb.displacement()[k]));
    scale = std::max(scale, std::abs(sb.displacement()[k]));
  }
  std::printf(
      "[measured] strip with a 2 mm half: per-element thickness vs two sections: mass %.6e / "
      "%.6e kg, largest |u| %.4e m, largest difference %.2e of it; plastic work %.4e / %.4e J\n",
      sa.total_mass_kg(), sb.total_mass_kg(), scale, worst / scale, sa.energy().internal_J,
      sb.energy().internal_J);
  EXPECT_GT(scale, 1e-4);  // it moved (0.1 mm and more)
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_NEAR(sa.energy().internal_J, sb.energy().internal_J, 1e-9 * sb.energy().internal_J);
}

}  // namespace
}  // namespace crashlink
