// Deck mistakes: each stops the reading with "file:line: *KEYWORD field NAME (columns a-b) =
// value: what; fix" (or "file:line: *KEYWORD: what; fix"), nothing built (docs/decks.md "Errors").
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

/// A valid one-hexahedron deck in mm-t-s, one string per line (line i + 1 of the file).
std::vector<std::string> cube() {
  return {
      "*KEYWORD",                                                                          // 1
      "*NODE",                                                                             // 2
      "       1     0.0             0.0             0.0",                                  // 3
      "       2     1.0             0.0             0.0",                                  // 4
      "       3     1.0             1.0             0.0",                                  // 5
      "       4     0.0             1.0             0.0",                                  // 6
      "       5     0.0             0.0             1.0",                                  // 7
      "       6     1.0             0.0             1.0",                                  // 8
      "       7     1.0             1.0             1.0",                                  // 9
      "       8     0.0             1.0             1.0",                                  // 10
      "*ELEMENT_SOLID",                                                                    // 11
      "       1       1       1       2       3       4       5       6       7       8",  // 12
      "*PART",                                                                             // 13
      "cube",                                                                              // 14
      "         1         1         1",                                                    // 15
      "*SECTION_SOLID",                                                                    // 16
      "         1         1",                                                              // 17
      "*MAT_ELASTIC",                                                                      // 18
      "         1   7.85e-9  210000.0       0.3",                                          // 19
      "*CONTROL_TERMINATION",                                                              // 20
      "    1.0e-5",                                                                        // 21
      "*END",                                                                              // 22
  };
}

class DeckErrors : public ::testing::Test {
 protected:
  /// The message of reading `lines` as err.k, with the folder left out of the file name.
  std::string error_of(const std::vector<std::string>& lines, const std::string& units = "mm-t-s",
                       const std::vector<std::string>& ignore = {}) {
    std::string text;
    for (const auto& l : lines) text += l + "\n";
    const std::string path = dir_.write("err.k", text);
    std::string msg = testing::input_error([&] { read_deck(path, {units, ignore}); });
    for (auto at = msg.find(dir_.path("")); at != std::string::npos; at = msg.find(dir_.path("")))
      msg.erase(at, dir_.path("").size());
    return msg;
  }
  testing::DeckFolder dir_;
};

TEST_F(DeckErrors, TheValidCubeReads) {
  EXPECT_EQ(error_of(cube()), "");
}

TEST_F(DeckErrors, UnsupportedKeywordListsTheSupportedOnes) {
  auto d = cube();
  d.insert(d.begin() + 21, {"*ELEMENT_BEAM", "       9       1       1       2"});
  const std::string msg = error_of(d);
  EXPECT_EQ(
      msg.rfind("err.k:22: *ELEMENT_BEAM: not supported; fix: remove it, or pass --ignore "
                "ELEMENT_BEAM to skip it (what it does is then missing from the run). "
                "Supported: *TITLE *NODE *ELEMENT_SHELL *ELEMENT_SHELL_THICKNESS *ELEMENT_SOLID "
                "*PART *PART_INERTIA *SECTION_SHELL(_TITLE)",
                0),
      0u)
      << msg;
  EXPECT_NE(msg.find("*MAT_PIECEWISE_LINEAR_PLASTICITY(_TITLE)"), std::string::npos);
  EXPECT_EQ(error_of(d, "mm-t-s", {"ELEMENT_BEAM"}), "");  // skipped on request
}

TEST_F(DeckErrors, IgnoringAKeywordTheDeckLacks) {
  EXPECT_EQ(error_of(cube(), "mm-t-s", {"ELEMENT_BEAM"}),
            "--ignore ELEMENT_BEAM: the deck has no such keyword; fix: remove it from --ignore "
            "(keywords are written without '*', e.g. --ignore ELEMENT_BEAM)");
}

TEST_F(DeckErrors, UnsupportedSolidFormulation) {
  auto d = cube();
  d[16] = "         1         2";
  EXPECT_EQ(error_of(d),
            "err.k:17: *SECTION_SOLID field ELFORM (columns 11-20) = 2: crashlink computes the "
            "one-point hexahedron (ELFORM 1) only; fix: write ELFORM 1 (or blank)");
}

TEST_F(DeckErrors, ElementOnAnUndefinedNode) {
  auto d = cube();
  d[11] = "       1       1       1       2       3       4       5       6       7      99";
  EXPECT_EQ(error_of(d),
            "err.k:12: *ELEMENT_SOLID field N8 (columns 73-80) = 99: node 99 is not defined; "
            "fix: add it under *NODE or correct the id");
}

TEST_F(DeckErrors, DuplicateNodeId) {
  auto d = cube();
  d[9] = "       1     0.0             1.0             1.0";
  EXPECT_EQ(error_of(d),
            "err.k:10: *NODE field NID (columns 1-8) = 1: node 1 is already defined at err.k:3; "
            "fix: give each node its own id");
}

TEST_F(DeckErrors, PartWithoutMaterialOrSection) {
  auto d = cube();
  d[14] = "         1         1         5";
  EXPECT_EQ(error_of(d),
            "err.k:15: *PART field MID (columns 21-30) = 5: material 5 is not defined; fix: add "
            "a *MAT_... card with MID 5");
  d[14] = "         1         3         1";
  EXPECT_EQ(error_of(d),
            "err.k:15: *PART field SECID (columns 11-20) = 3: section 3 is not defined; fix: add "
            "*SECTION_SHELL or *SECTION_SOLID 3");
}

TEST_F(DeckErrors, ElementOfAnUndefinedPart) {
  auto d = cube();
  d[11] = "       1       2       1       2       3       4       5       6       7       8";
  EXPECT_EQ(error_of(d),
            "err.k:12: *ELEMENT_SOLID field PID (columns 9-16) = 2: part 2 is not defined; fix: "
            "add a *PART with PID 2");
}

TEST_F(DeckErrors, DegenerateHexahedron) {
  auto d = cube();
  d[11] = "       1       1       1       2       3       4       5       6       7       7";
  EXPECT_EQ(error_of(d),
            "err.k:12: *ELEMENT_SOLID field N8 (columns 73-80) = 7: repeats a corner: degenerate "
            "hexahedra (prisms, tetrahedra) are not computed yet; fix: mesh the part with 8 "
            "distinct corners per element");
}

TEST_F(DeckErrors, KinematicHardeningRefused) {
  auto d = cube();
  d[17] = "*MAT_PLASTIC_KINEMATIC";
  d[18] = "         1   7.85e-9  210000.0       0.3     250.0    1000.0";
  EXPECT_EQ(error_of(d),
            "err.k:19: *MAT_PLASTIC_KINEMATIC field BETA (columns 61-70) = (blank): crashlink "
            "computes isotropic hardening (BETA = 1) only, kinematic hardening (BETA < 1; blank "
            "is 0) is not computed; fix: write BETA 1.0");
}

TEST_F(DeckErrors, RateTablesRefused) {
  auto d = cube();
  d[17] = "*MAT_PIECEWISE_LINEAR_PLASTICITY";
  d[18] = "         1   7.85e-9  210000.0       0.3     250.0    1000.0";
  d.insert(d.begin() + 19, "      40.0       5.0                   7");
  EXPECT_EQ(error_of(d),
            "err.k:20: *MAT_PIECEWISE_LINEAR_PLASTICITY field LCSR (columns 31-40) = 7: a table "
            "of yield-stress scale factors over strain rate (LCSR) is not read; fix: write LCSR 0 "
            "and give C and P (Cowper-Symonds)");
}

TEST_F(DeckErrors, NotANumber) {
  auto d = cube();
  d[18] = "         1   7.85e-9   2.1e5x        0.3";
  EXPECT_EQ(error_of(d),
            "err.k:19: *MAT_ELASTIC field E (columns 21-30) = 2.1e5x: not a number; fix: write a "
            "number (e.g. 2.1e5), &name of a *PARAMETER, or leave it blank for the default");
}

TEST_F(DeckErrors, UndefinedParameter) {
  auto d = cube();
  d[20] = "     &tend";
  EXPECT_EQ(error_of(d),
            "err.k:21: *CONTROL_TERMINATION field ENDTIM (columns 1-10) = &tend: parameter 'tend' "
            "is not defined; fix: define it in a *PARAMETER (R tend 1.0) or *PARAMETER_EXPRESSION "
            "before this card");
}

TEST_F(DeckErrors, UnitsMissingOrUnknownNameTheCandidates) {
  // Not given and inferable (steel in mm-t-s): read in mm-t-s, said so.
  EXPECT_EQ(error_of(cube(), ""), "");
  std::string text;
  for (const auto& l : cube()) text += l + "\n";
  const auto r = read_deck(dir_.write("ok.k", text), {"", {}});
  EXPECT_EQ(r.units, "mm-t-s");
  EXPECT_DOUBLE_EQ(r.model.materials[0].density_kg_m3, 7850.0);
  ASSERT_FALSE(r.messages.empty());
  EXPECT_EQ(r.messages[0],
            "units: --units not given; read in mm-t-s, the only system in which every "
            "material's wave speed sqrt(E/RO) and density are those of a crash material ([100, "
            "20000] m/s, [10, 25000] kg/m^3); pass --units to choose");
  // Not given and not inferable: RO without its e-9 is no crash material in any system.
  auto d = cube();
  d[18] = "         1      7.85  210000.0       0.3";
  EXPECT_EQ(error_of(d, ""),
            "err.k:0: --units: not given; a deck writes no units down, and no single system makes "
            "every material's wave speed and density those of a crash material; fix: pass "
            "--units with one of mm-t-s, m-kg-s, mm-kg-ms, mm-g-ms, cm-g-us, in-lbf-s (the "
            "materials' wave speeds fit: m-kg-s, mm-kg-ms, mm-g-ms; their densities too: none)");
  EXPECT_NE(error_of(cube(), "mm-t-ms").find("--units: 'mm-t-ms' is not a known system"),
            std::string::npos);
}

TEST_F(DeckErrors, EmptyIgnoreEntryIsRefused) {
  EXPECT_EQ(error_of(cube(), "mm-t-s", {""}),
            "err.k:0: --ignore: an empty keyword name; fix: list keywords without '*' and "
            "without empty entries, e.g. --ignore ELEMENT_BEAM,DAMPING_GLOBAL");
}

TEST_F(DeckErrors, ImplausibleWaveSpeed) {
  auto d = cube();
  d[18] = "         1      7.85  210000.0       0.3";  // RO without its e-9
  EXPECT_EQ(error_of(d),
            "err.k:19: *MAT_ELASTIC field E (columns 21-30) = 210000.0: with RO = 7.85 and "
            "--units mm-t-s, the wave speed sqrt(E/RO) is 0.1636 m/s, outside the [100, 20000] m/s "
            "of crash materials (steel 5200); fix: check E and RO, or the units: the deck fits "
            "--units m-kg-s or mm-kg-ms or mm-g-ms");
}

TEST_F(DeckErrors, NoEndTime) {
  auto d = cube();
  d.erase(d.begin() + 19, d.begin() + 21);
  EXPECT_EQ(error_of(d),
            "err.k:0: *CONTROL_TERMINATION: missing: the deck sets no end time; fix: add "
            "*CONTROL_TERMINATION with ENDTIM");
}

TEST_F(DeckErrors, ShellElementInASolidPart) {
  auto d = cube();
  d.insert(d.begin() + 12, {"*ELEMENT_SHELL", "       2       1       1       2       3       4"});
  EXPECT_EQ(error_of(d),
            "err.k:14: *ELEMENT_SHELL field PID (columns 9-16) = 1: part 1 has *SECTION_SOLID 1 "
            "(err.k:19); fix: give the part a *SECTION_SHELL");
}

TEST_F(DeckErrors, DuplicateElementId) {
  auto d = cube();
  d.insert(d.begin() + 12,
           "       1       1       5       6       7       8       1       2       3       4");
  EXPECT_EQ(error_of(d),
            "err.k:13: *ELEMENT_SOLID field EID (columns 1-8) = 1: *ELEMENT_SOLID 1 is already "
            "defined; fix: give each solid its own id");
}

TEST_F(DeckErrors, ConstraintOnAnUndefinedNodeSet) {
  auto d = cube();
  d.insert(d.begin() + 21, {"*BOUNDARY_SPC_SET", "         4         0         1"});
  EXPECT_EQ(error_of(d),
            "err.k:23: *BOUNDARY_SPC_SET field NSID (columns 1-10) = 4: node set 4 is not "
            "defined; fix: add *SET_NODE_LIST 4");
}

TEST_F(DeckErrors, ShellSectionChecks) {
  auto d = cube();
  d[15] = "*SECTION_SHELL";
  d[16] = "         1        16";
  EXPECT_EQ(error_of(d),
            "err.k:17: *SECTION_SHELL field ELFORM (columns 11-20) = 16: crashlink computes the "
            "Belytschko-Tsay shell (ELFORM 2) only; fix: write ELFORM 2 (or blank)");
  d[16] = "         1         2";
  d.insert(d.begin() + 17, "       1.0");
  EXPECT_EQ(error_of(d),
            "err.k:17: *SECTION_SHELL field NIP (columns 31-40) = (blank): 2 Gauss points "
            "through the thickness (LS-DYNA's default for a blank NIP): crashlink integrates "
            "with 3 to 9; fix: write NIP 3 (elastic) or 5 (plasticity)");
}

TEST_F(DeckErrors, AKeywordWithoutItsCards) {
  auto d = cube();
  d.insert(d.begin() + 19, "*MAT_ELASTIC");
  EXPECT_EQ(error_of(d),
            "err.k:20: *MAT_ELASTIC: its cards are missing (the next keyword or the end of the "
            "file follows); fix: add them or remove the keyword");
  d[19] = "*DEFINE_CURVE";
  d.insert(d.begin() + 20, "         7");
  EXPECT_EQ(error_of(d),
            "err.k:20: *DEFINE_CURVE: the curve has no point; fix: add its points (A, O) after "
            "LCID");
}

TEST_F(DeckErrors, ADataCardBeforeAnyKeyword) {
  auto d = cube();
  d.insert(d.begin(), "       1     0.0");
  EXPECT_EQ(error_of(d),
            "err.k:1: (data card): no keyword before it; fix: start the file with *KEYWORD and "
            "put every card under its keyword");
}

}  // namespace
}  // namespace crashlink::deck
