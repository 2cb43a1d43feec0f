// *DATABASE_GLSTAT (and the other ASCII histories), *DATABASE_BINARY_D3PLOT and
// *DATABASE_HISTORY_NODE(_ID|_SET) read into the model: the history and field intervals and the
// probes (docs/decks.md "Keywords"), and their mistakes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

class DeckOutput : public testing::DeckLinesTest {};

TEST_F(DeckOutput, IntervalsAndProbes) {
  const auto d = testing::two_cubes_with(
      {"*DATABASE_GLSTAT", "   2.0E-07         3", "*DATABASE_NODOUT", "   1.0E-07         3",
       "*DATABASE_ELOUT", "   5.0E-08", "*DATABASE_BINARY_D3PLOT", "   1.0E-06",
       "*DATABASE_HISTORY_NODE", "         8         1         8", "*DATABASE_HISTORY_NODE_ID",
       "        16tip of the upper cube", "*SET_NODE_LIST", "         3",
       "         9        10         1", "*DATABASE_HISTORY_NODE_SET", "         3"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  const auto& m = r.model;
  // mm-t-s: the deck's seconds are seconds; the smallest ASCII interval (NODOUT) for every
  // history, *DATABASE_ELOUT without effect.
  EXPECT_DOUBLE_EQ(m.controls.history_interval_s, 1.0e-7);
  EXPECT_DOUBLE_EQ(m.controls.field_interval_s, 1.0e-6);
  // Node 8 twice and node 1 again in set 3: one probe each, in the order first met.
  ASSERT_EQ(m.probes.size(), 5u);
  const char* names[] = {"node_8", "node_1", "tip of the upper cube", "node_9", "node_10"};
  const std::int64_t nids[] = {8, 1, 16, 9, 10};
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(m.probes[k].name, names[k]);
    EXPECT_EQ(m.probes[k].kind, model::Probe::Kind::Node);
    EXPECT_EQ(m.nodes.id[static_cast<std::size_t>(m.probes[k].index)], nids[k]);
  }
  bool elout = false, one_interval = false;
  for (const auto& s : r.messages) {
    elout = elout || s == "accepted without effect (crashlink writes its own output): "
                          "*DATABASE_ELOUT";
    one_interval = one_interval ||
                   s == "crashlink writes every history at one interval: 1e-07 s, the smallest "
                        "DT of *DATABASE_GLSTAT, *DATABASE_NODOUT";
  }
  EXPECT_TRUE(elout);
  EXPECT_TRUE(one_interval);
}

TEST_F(DeckOutput, StateCountHeadingsAndFreeSetMembers) {
  // NPLTC 4 over ENDTIM 1e-5 s: a state every 2.5e-6 s, in place of DT; three headings 'tip'
  // (and one 'tip_6') made unique; node 40 of set 3 is in no element: left out.
  const auto d = testing::two_cubes_with(
      {"*NODE", "      40             9.0             9.0", "*DATABASE_BINARY_D3PLOT",
       "   1.0E-06                             4", "*DATABASE_HISTORY_NODE_ID", "         5tip",
       "         6tip", "         7tip_6", "         8tip", "*SET_NODE_LIST", "         3",
       "        40         9", "*DATABASE_HISTORY_NODE_SET", "         3"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  const auto& m = r.model;
  EXPECT_DOUBLE_EQ(m.controls.field_interval_s, 2.5e-6);
  ASSERT_EQ(m.probes.size(), 5u);
  const char* names[] = {"tip", "tip_6", "tip_6_7", "tip_8", "node_9"};
  for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(m.probes[k].name, names[k]);
}

TEST_F(DeckOutput, WithoutThemEveryCycleAndTheEnds) {
  DeckRead r;
  ASSERT_EQ(read(testing::two_cubes(), &r), "");
  EXPECT_EQ(r.model.controls.history_interval_s, 0.0);
  EXPECT_EQ(r.model.controls.field_interval_s, 0.0);
  EXPECT_TRUE(r.model.probes.empty());
}

// *DATABASE_RBDOUT: every rigid body's motion is a probe named after it (the HIC channel of a
// headform), before the node probes; its DT is a history interval like the others'.
TEST_F(DeckOutput, RigidBodyOutputProbesEveryBody) {
  auto d = testing::two_cubes();
  for (auto& l : d)
    if (l == "         2         1         1") l = "         2         2         2";
  d.insert(d.end(), {"*SECTION_SOLID", "         2         1", "*MAT_RIGID",
                     "         2   7.85e-9  210000.0       0.3", "*DATABASE_HISTORY_NODE_ID",
                     "         1corner", "*DATABASE_RBDOUT", "    1.0e-6"});
  DeckRead r;
  ASSERT_EQ(read(d, &r), "");
  ASSERT_EQ(r.model.probes.size(), 2u);
  EXPECT_EQ(r.model.probes[0].name, "upper");
  EXPECT_EQ(r.model.probes[0].kind, model::Probe::Kind::RigidBody);
  EXPECT_EQ(r.model.probes[0].index, 0);
  EXPECT_EQ(r.model.probes[1].name, "corner");
  EXPECT_DOUBLE_EQ(r.model.controls.history_interval_s, 1e-6);
}

TEST_F(DeckOutput, MistakesNameTheirField) {
  struct Mistake {
    std::vector<std::string> deck;
    std::string message;
  };
  const Mistake mistakes[] = {
      {testing::two_cubes_with({"*DATABASE_GLSTAT", "   1.0E-07         3         5"}),
       "c.k:35: *DATABASE_GLSTAT field LCUR (columns 21-30) = 5: an output interval from a curve "
       "is not read; fix: leave it blank and give DT"},
      {testing::two_cubes_with({"*DATABASE_BINARY_D3PLOT", "  -1.0E-06"}),
       "c.k:35: *DATABASE_BINARY_D3PLOT field DT (columns 1-10) = -1.0E-06: an output interval "
       "must be >= 0; fix: write the interval (0: no output)"},
      {testing::two_cubes_with({"*DATABASE_HISTORY_NODE", "         1        99"}),
       "c.k:35: *DATABASE_HISTORY_NODE field ID2 (columns 11-20) = 99: node 99 is not defined; "
       "fix: add it under *NODE or correct the id"},
      {testing::two_cubes_with({"*DATABASE_HISTORY_NODE_SET", "         0         7"}),
       "c.k:35: *DATABASE_HISTORY_NODE_SET field ID2 (columns 11-20) = 7: node set 7 is not "
       "defined; fix: add *SET_NODE_LIST 7"},
      {testing::two_cubes_with({"*NODE", "      40             9.0             9.0",
                                "*DATABASE_HISTORY_NODE_ID", "        40"}),
       "c.k:37: *DATABASE_HISTORY_NODE_ID field ID (columns 1-10) = 40: node 40 belongs to no "
       "element (crashlink leaves such nodes out); fix: probe a node of an element"},
  };
  for (const auto& k : mistakes) EXPECT_EQ(read(k.deck), k.message);
}

}  // namespace
}  // namespace crashlink::deck
