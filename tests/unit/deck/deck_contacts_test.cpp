// *CONTACT_*, *DEFINE_BOX with *SET_NODE_GENERAL and *DEFINE_COORDINATE_SYSTEM read into the
// model (docs/decks.md "Contacts", "Sets", "Coordinate systems"), and their mistakes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

class DeckContacts : public testing::DeckLinesTest {};

TEST_F(DeckContacts, TwoPassOnePassAndSingleSurfaceMapOntoTheModel) {
  auto d = testing::two_cubes();
  d.insert(
      d.end(),
      {"*SET_PART_LIST", "        10", "         2",
       // two-pass, by parts, friction with decay, SOFT 1 with SOFSCL 0.2, SFS = SFM = 2
       "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID", "         7lid on box",
       "         2         1         3         3", "       0.3       0.2       0.5",
       "       2.0       2.0", "         1       0.2",
       // one-pass, slave node set, master part set, no optional cards
       "*SET_NODE_LIST", "        20", "         9        10        11        12",
       "*CONTACT_NODES_TO_SURFACE", "        20        10         4         2", "       0.1", "",
       // single surface over all parts (SSID 0), SOFT 0
       "*CONTACT_AUTOMATIC_SINGLE_SURFACE", "         0", "", "", "         0"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  const auto& c = r.model.contacts;
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].name, "lid on box");
  EXPECT_EQ(c[0].kind, model::ContactKind::SurfaceToSurface);
  EXPECT_EQ(c[0].slave_nodes.size(), 8u);  // the upper cube's
  for (auto n : c[0].slave_nodes) EXPECT_GE(r.model.nodes.id[static_cast<std::size_t>(n)], 9);
  ASSERT_EQ(c[0].master_parts.size(), 1u);
  EXPECT_EQ(r.model.parts[static_cast<std::size_t>(c[0].master_parts[0])].name, "lower");
  EXPECT_DOUBLE_EQ(c[0].static_friction, 0.3);
  EXPECT_DOUBLE_EQ(c[0].dynamic_friction, 0.2);
  EXPECT_DOUBLE_EQ(c[0].friction_decay_s_m, 0.5 * 1.0 / 1e-3);  // s/mm -> s/m
  EXPECT_DOUBLE_EQ(c[0].penalty_scale, 0.2);
  EXPECT_TRUE(c[0].soft);
  EXPECT_DOUBLE_EQ(c[0].soft_scale, 0.2);

  EXPECT_EQ(c[1].name, "contact_2");
  EXPECT_EQ(c[1].kind, model::ContactKind::NodeToSurface);
  EXPECT_EQ(c[1].slave_nodes.size(), 4u);
  ASSERT_EQ(c[1].master_parts.size(), 1u);
  EXPECT_EQ(r.model.parts[static_cast<std::size_t>(c[1].master_parts[0])].name, "upper");
  EXPECT_DOUBLE_EQ(c[1].static_friction, 0.1);
  EXPECT_DOUBLE_EQ(c[1].dynamic_friction, 0.1);  // FD 0 and DC 0: mu = FS, as LS-DYNA
  EXPECT_DOUBLE_EQ(c[1].penalty_scale, 0.1);
  EXPECT_FALSE(c[1].soft);

  EXPECT_EQ(c[2].kind, model::ContactKind::SingleSurface);
  EXPECT_EQ(c[2].master_parts.size(), 2u);
  // The non-automatic form is computed as the automatic one, and the user is told.
  bool told = false;
  for (const auto& m : r.messages)
    told = told ||
           m.find("*CONTACT_NODES_TO_SURFACE: computed as its automatic form") != std::string::npos;
  EXPECT_TRUE(told);
}

TEST_F(DeckContacts, BoxSetsAndALocalFrameForTheInitialVelocity) {
  auto d = testing::two_cubes();
  d.insert(
      d.end(),
      {// the upper cube's top face: z in [2.4, 2.6]
       "*DEFINE_BOX", "         1     -10.0      10.0     -10.0      10.0       2.4       2.6",
       "*SET_NODE_GENERAL", "         5", "BOX                1", "*SET_NODE_GENERAL", "         6",
       "PART               1", "NODE               9", "*BOUNDARY_SPC_SET",
       "         5         0         1         1         1",
       // local x along global y, local y along -x: local (2, 0, 0) mm/s -> global (0, 2, 0)
       "*DEFINE_COORDINATE_SYSTEM",
       "         3       0.0       0.0       0.0       0.0"
       "       1.0       0.0",
       "      -1.0       0.0       0.0", "*INITIAL_VELOCITY_GENERATION",
       "         6         3       0.0    2000.0       0.0       0.0         0         3", ""});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  const auto& m = r.model;
  EXPECT_EQ(std::count(m.fixed.begin(), m.fixed.end(), model::kUx | model::kUy | model::kUz), 4);
  for (std::size_t i = 0; i < m.fixed.size(); ++i) {
    if (m.fixed[i] != 0) {
      EXPECT_NEAR(m.nodes.x0[3 * i + 2], 2.5e-3, 1e-12);
    }
  }
  ASSERT_EQ(m.initial_velocities.size(), 1u);
  EXPECT_EQ(m.initial_velocities[0].nodes.size(), 9u);  // part 1's eight and node 9
  EXPECT_NEAR(m.initial_velocities[0].velocity_m_s[0], 0.0, 1e-15);
  EXPECT_NEAR(m.initial_velocities[0].velocity_m_s[1], 2.0, 1e-15);
  EXPECT_NEAR(m.initial_velocities[0].velocity_m_s[2], 0.0, 1e-15);
}

struct Mistake {
  const char* what;
  std::vector<std::string> cards;
  std::string message;
};

TEST_F(DeckContacts, MistakesNameTheirField) {
  const Mistake mistakes[] = {
      {"segment set master surface",
       {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         2         1         3         0"},
       "c.k:35: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE field MSTYP (columns 31-40) = 0: surface "
       "type 0 is not read: crashlink takes a contact surface as parts (3), a part set (2) or "
       "all parts (5); fix: name the parts"},
      {"SOFT 2",
       {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         2         1         3         3", "", "",
        "         2"},
       "c.k:38: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE field SOFT (columns 1-10) = 2: crashlink "
       "computes SOFT 0 (penalty from the segment stiffness) and SOFT 1 (also a stiffness from "
       "the nodal mass and step); the segment-based SOFT 2 is not computed; fix: write 0 or 1"},
      {"SFS differs from SFM",
       {"*CONTACT_SURFACE_TO_SURFACE", "         2         1         3         3", "",
        "       1.0       2.0"},
       "c.k:37: *CONTACT_SURFACE_TO_SURFACE field SFM (columns 11-20) = 2.0: crashlink has one "
       "penalty scale per contact and SFS = 1; fix: write SFM = SFS"},
      {"contact damping",
       {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         2         1         3         3",
        "       0.1       0.1       0.0       0.0      20.0"},
       "c.k:36: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE field VDC (columns 41-50) = 20.0: contact "
       "damping (VDC) is not computed; fix: write 0"},
      {"undefined master part",
       {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         2         9         3         3"},
       "c.k:35: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE field MSID (columns 11-20) = 9: part 9 is "
       "not defined; fix: correct the id"},
      {"cards missing",
       {"*CONTACT_AUTOMATIC_SINGLE_SURFACE"},
       "c.k:34: *CONTACT_AUTOMATIC_SINGLE_SURFACE: its cards are missing (the next keyword or "
       "the end of the file follows); fix: add them or remove the keyword"},
      {"undefined box",
       {"*SET_NODE_GENERAL", "         5", "BOX                4"},
       "c.k:36: *SET_NODE_GENERAL field E1 (columns 11-20) = 4: *DEFINE_BOX 4 is not defined; "
       "fix: correct the id or define it"},
      {"unsupported set option",
       {"*SET_NODE_GENERAL", "         5", "SEG                4"},
       "c.k:36: *SET_NODE_GENERAL field OPTION (columns 1-10) = SEG: crashlink reads the "
       "options ALL, NODE (node ids), PART (part ids) and BOX (box ids) of *SET_NODE_GENERAL; "
       "fix: write one of them, or list the nodes under *SET_NODE_LIST"},
      {"undefined coordinate system",
       {"*INITIAL_VELOCITY_GENERATION",
        "         1         2       0.0    2000.0       0.0       0.0         0         4", ""},
       "c.k:35: *INITIAL_VELOCITY_GENERATION field ICID (columns 71-80) = 4: coordinate system "
       "4 is not defined; fix: add *DEFINE_COORDINATE_SYSTEM 4 or write 0 (global axes)"},
      {"degenerate coordinate system",
       {"*DEFINE_COORDINATE_SYSTEM", "         3       0.0       0.0       0.0       1.0",
        "       2.0       0.0       0.0"},
       "c.k:35: *DEFINE_COORDINATE_SYSTEM field XL (columns 41-50) = 1.0: O, L and P must not "
       "lie on one line (O->L is the local x axis, P a point of the local x-y plane off that "
       "axis); fix: correct XL, YL, ZL or XP, YP, ZP"},
      {"friction table (FS 2)",
       {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "         2         1         3         3",
        "       2.0         5"},
       "c.k:36: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE field FS (columns 1-10) = 2.0: friction "
       "from tables (FS < 0, or FS = 2 with FD a table id) is not computed; fix: write the "
       "static coefficient (0.1 steel on steel, lubricated)"},
      {"empty slave node set",
       {"*DEFINE_BOX", "         1     100.0     101.0       0.0       1.0       0.0       1.0",
        "*SET_NODE_GENERAL", "        20", "BOX                1", "*CONTACT_NODES_TO_SURFACE",
        "        20         1         4         3"},
       "c.k:40: *CONTACT_NODES_TO_SURFACE field SSID (columns 1-10) = 20: the slave surface "
       "holds no node of an element; fix: correct the set"},
      {"an undefined box in E2 (E1 blank)",
       {"*DEFINE_BOX", "         1       0.0       1.0       0.0       1.0       0.0       1.0",
        "*SET_NODE_GENERAL", "         5", "BOX                          4"},
       "c.k:38: *SET_NODE_GENERAL field E2 (columns 21-30) = 4: *DEFINE_BOX 4 is not defined; "
       "fix: correct the id or define it"},
      {"titled coordinate system without card 2",
       {"*DEFINE_COORDINATE_SYSTEM_TITLE", "frame",
        "         3       0.0       0.0       0.0"
        "       1.0"},
       "c.k:36: *DEFINE_COORDINATE_SYSTEM_TITLE: card 2 (XP YP ZP, a point in the local x-y "
       "plane) is missing; fix: add it"},
  };
  const std::size_t base = testing::two_cubes().size();
  ASSERT_EQ(base, 33u);  // the messages' line numbers start at 34
  for (const auto& k : mistakes) {
    SCOPED_TRACE(k.what);
    auto d = testing::two_cubes();
    d.insert(d.end(), k.cards.begin(), k.cards.end());
    EXPECT_EQ(read(d), k.message);
  }
}

TEST_F(DeckContacts, RepeatedHeadingsGetDistinctNamesAndLaterCardsAreNoted) {
  auto d = testing::two_cubes();
  d.insert(d.end(),
           {"*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID", "         5lid",
            "         2         1         3         3", "", "", "", "",
            // card C with IGAP 1 (its default), card D written
            "         1         0", "         0", "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID",
            "         6lid", "         2         1         3         3",
            "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID", "         7",
            "         2         1         3         3"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  ASSERT_EQ(r.model.contacts.size(), 3u);
  EXPECT_EQ(r.model.contacts[0].name, "lid");
  EXPECT_EQ(r.model.contacts[1].name, "lid (CID 6)");
  EXPECT_EQ(r.model.contacts[2].name, "contact_7");
  bool noted = false;
  for (const auto& m : r.messages)
    noted =
        noted || m.find("optional cards D and later are read without effect") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace crashlink::deck

namespace crashlink::deck {
namespace {

class DeckSegmentSets : public testing::DeckLinesTest {};

// SSTYP 0: the slave side as a *SET_SEGMENT, its faces kept in order (the two-pass contact's
// slave faces) and their nodes the slave nodes.
TEST_F(DeckSegmentSets, SlaveFacesAreTheSegmentsGiven) {
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes_with({"*SET_SEGMENT_TITLE", "lower top", "         3",
                                          "         5         6         8         7",
                                          "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
                                          "         3         2         0         3", "", "",
                                          "*CONTACT_AUTOMATIC_NODES_TO_SURFACE",
                                          "         3         2         0         3", "", ""}),
                 &r),
            "");
  ASSERT_EQ(r.model.contacts.size(), 2u);
  const auto& c = r.model.contacts[0];
  ASSERT_EQ(c.slave_faces.size(), 4u);
  const std::vector<std::int64_t> want{5, 6, 8, 7};
  for (std::size_t j = 0; j < 4; ++j)
    EXPECT_EQ(r.model.nodes.id[static_cast<std::size_t>(c.slave_faces[j])], want[j]);
  EXPECT_EQ(c.slave_nodes.size(), 4u);
  EXPECT_TRUE(r.model.contacts[1].slave_faces.empty()) << "one pass: the nodes only";
  EXPECT_EQ(r.model.contacts[1].slave_nodes, c.slave_nodes);
}

TEST_F(DeckSegmentSets, MistakesNameTheirField) {
  const std::string contact = "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE";
  const std::string card = "         3         2         0         3";
  // not a face of an element (a diagonal plane of the cube)
  EXPECT_NE(read(testing::two_cubes_with({"*SET_SEGMENT", "         3",
                                          "         1         2         8         7", contact, card,
                                          "", ""}))
                .find("c.k:36: *SET_SEGMENT field N1 (columns 1-10) = 1: is not a face of an "
                      "element"),
            std::string::npos);
  // a corner twice that is not the triangle's N3 = N4
  EXPECT_NE(read(testing::two_cubes_with(
                     {"*SET_SEGMENT", "         3", "         5         5         8         7"}))
                .find("field N2 (columns 11-20) = 5: repeats a corner"),
            std::string::npos);
  // the set is not there
  EXPECT_NE(read(testing::two_cubes_with({contact, card, "", ""}))
                .find("segment set 3 is not defined (SSTYP 0: a segment set)"),
            std::string::npos);
  // two sets with one id
  EXPECT_NE(read(testing::two_cubes_with(
                     {"*SET_SEGMENT", "         3", "         5         6         8         7",
                      "*SET_SEGMENT", "         3", "         5         6         8         7"}))
                .find("segment set 3 is already defined"),
            std::string::npos);
}

}  // namespace
}  // namespace crashlink::deck
