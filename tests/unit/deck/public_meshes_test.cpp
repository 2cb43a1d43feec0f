// The public meshes (MIT, ansys/example-data; tests/data/decks/ansys/README.md) read without
// error once completed with the parts, sections and materials their scripts describe: every
// element on defined nodes, every node and element counted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "solver/deck/model_from_deck.h"
#include "tests/unit/deck/deck_test_support.h"

namespace crashlink::deck {
namespace {

struct PublicMesh {
  const char* folder;
  const char* mesh;
  const char* units;
  const char* parts;  ///< *PART, *SECTION_* and *MAT_* cards completing the mesh
  std::size_t nodes, shells, solids;
};

constexpr const char* kSteelMmTS =
    "*SECTION_SOLID\n         1         1\n*SECTION_SHELL\n         2         2    0.8333"
    "         3\n       1.0\n*MAT_ELASTIC\n         1   7.85e-9  210000.0       0.3\n";
constexpr const char* kSteelKgMmMs =
    "*SECTION_SOLID\n         1         1\n*SECTION_SHELL\n         2         2    0.8333"
    "         3\n      11.0\n*MAT_ELASTIC\n         1   7.86e-6     200.0       0.3\n";
constexpr const char* kAluminiumInLbfS =
    "*SECTION_SHELL\n         2         2    0.8333         3\n     0.002\n*MAT_ELASTIC\n"
    "         1   2.59e-4     1.0e7      0.33\n";

std::string part(int pid, int secid) {
  return fmt::format("*PART\npart {}\n{:10d}{:10d}{:10d}\n", pid, pid, secid, 1);
}

/// The mesh included by a deck that adds `parts` and an end time; read in `units`.
model::Model complete_and_read(const testing::DeckFolder& dir, const std::string& mesh,
                               const std::string& units, const std::string& parts,
                               const std::vector<std::string>& ignore, DeckRead* read = nullptr) {
  const std::string deck = dir.write("complete.k", "*KEYWORD\n*INCLUDE\n" + mesh + "\n" + parts +
                                                       "*CONTROL_TERMINATION\n    1.0e-3\n*END\n");
  DeckRead r = read_deck(deck, {units, ignore});
  if (read) *read = r;
  return std::move(r.model);
}

TEST(DeckPublicMeshes, PendulumCopyReadsWithItsBeamsSkipped) {
  const std::string mesh =
      std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/ansys/John_Reid_Pendulum/nodes.k";
  testing::DeckFolder dir;
  const std::string parts = std::string(kSteelKgMmMs) + part(1, 2) + part(2, 2);
  // Strict by default: the beams stop the reading at their keyword.
  const std::string msg =
      testing::input_error([&] { complete_and_read(dir, mesh, "mm-kg-ms", parts, {}); });
  EXPECT_EQ(msg.rfind(mesh + ":803: *ELEMENT_BEAM: not supported; fix: remove it, or pass "
                             "--ignore ELEMENT_BEAM",
                      0),
            0u)
      << msg;
  DeckRead read;
  const auto m = complete_and_read(dir, mesh, "mm-kg-ms", parts, {"ELEMENT_BEAM"}, &read);
  EXPECT_EQ(m.element_count(), 768u);
  EXPECT_EQ(m.nodes.count(), 772u);  // 784, less the wires' 12 nodes (no element left)
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_DOUBLE_EQ(m.parts[0].thickness_m, 0.011);
  bool skipped = false;
  for (const auto& s : read.messages)
    skipped = skipped || s == "skipped on request (--ignore): *ELEMENT_BEAM (8 cards)";
  EXPECT_TRUE(skipped);
}

TEST(DeckPublicMeshes, SharedMeshesRead) {
  const std::filesystem::path root("/work/shared/decks/ansys-example-data");
  if (!std::filesystem::exists(root))
    GTEST_SKIP() << root << " is absent (the copy in tests/data is tested above)";
  const std::string mm_ts = kSteelMmTS;
  const PublicMesh meshes[] = {
      {"Taylor_Bar", "taylor_bar_mesh.k", "mm-t-s", "", 1122, 0, 768},
      {"Bar_Impact", "bar_impact_mesh.k", "mm-t-s", "", 1411, 256, 768},
      {"Buckling_Beer_Can", "mesh.k", "in-lbf-s", "", 3437, 3320, 0},
      {"John_Reid_Pipe", "nodes.k", "mm-kg-ms", "", 2049, 1400, 304},
  };
  const std::string parts[] = {
      mm_ts + part(1, 1),
      mm_ts + part(1, 1) + part(2, 2),
      std::string(kAluminiumInLbfS) + part(1, 2) + part(2, 2),
      std::string(kSteelKgMmMs) + part(1, 2) + part(2, 2) + part(3, 2) + part(4, 1),
  };
  testing::DeckFolder dir;
  for (std::size_t i = 0; i < std::size(meshes); ++i) {
    const auto& p = meshes[i];
    SCOPED_TRACE(p.folder);
    const std::string mesh = (root / p.folder / p.mesh).string();
    model::Model m;
    EXPECT_EQ(
        testing::input_error([&] { m = complete_and_read(dir, mesh, p.units, parts[i], {}); }), "");
    EXPECT_EQ(m.nodes.count(), p.nodes);
    std::size_t shells = 0, solids = 0;
    for (const auto& part_ : m.parts)
      (part_.kind == model::ElementKind::Shell4 ? shells : solids) += part_.element_count();
    EXPECT_EQ(shells, p.shells);
    EXPECT_EQ(solids, p.solids);
  }
}

}  // namespace
}  // namespace crashlink::deck
