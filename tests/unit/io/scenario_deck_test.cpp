// A scenario naming a keyword deck (`model: {deck, units, ignore}`, docs/decks.md "In a
// scenario"): the deck's model with the scenario's domains (by *PART PID or title), probes and
// control overrides; its hash covers the bytes of the deck and of every file it includes; the
// scenario's own mistakes (a missing deck, a bad unit system, sections the deck defines) are
// refused at their file:line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::io {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(CRASHLINK_TEST_DATA_DIR) / "data/decks/two_rates";

/// A copy of tests/data/decks/two_rates/ in a fresh temporary folder (removed at the end).
struct DeckCopy {
  fs::path dir;
  DeckCopy() {
    dir = fs::temp_directory_path() /
          ("crashlink_scenario_deck_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& f : fs::directory_iterator(kData))
      fs::copy(f.path(), dir / f.path().filename());
  }
  ~DeckCopy() { fs::remove_all(dir); }
  std::string yaml() const { return (dir / "two_rates.yaml").string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
  }
  std::string read(const std::string& name) const {
    std::ifstream in(dir / name, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

std::string message_of(const std::string& path) {
  try {
    (void)read_scenario(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ScenarioDeck, DomainsByPartIdAndTitleProbesAndControls) {
  const model::Model m = read_scenario((kData / "two_rates.yaml").string());
  EXPECT_EQ(m.name, "two-rate bar deck");
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[0].name, "coarse");
  EXPECT_EQ(m.parts[1].name, "fine");
  ASSERT_EQ(m.domains.size(), 2u);
  EXPECT_EQ(m.domains[0].name, "coarse");
  EXPECT_EQ(m.domains[0].parts, std::vector<int>{0});  // by PID 1
  EXPECT_EQ(m.domains[1].name, "fine");
  EXPECT_EQ(m.domains[1].parts, std::vector<int>{1});       // by title
  EXPECT_DOUBLE_EQ(m.controls.end_time_s, 1.0e-4);          // the deck's ENDTIM in s (kept)
  EXPECT_DOUBLE_EQ(m.controls.dt_scale, 0.9);               // the deck's TSSFAC (kept)
  EXPECT_DOUBLE_EQ(m.controls.history_interval_s, 1.0e-6);  // the scenario's override
  ASSERT_EQ(m.probes.size(), 1u);
  EXPECT_EQ(m.probes[0].name, "tip");
  EXPECT_EQ(m.nodes.id[static_cast<std::size_t>(m.probes[0].index)], 164);  // the deck's NID
}

TEST(ScenarioDeck, HashCoversTheDeckAndItsIncludesByteByByte) {
  const DeckCopy c;
  const std::string h = scenario_hash(c.yaml());
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(read_scenario_with_hash(c.yaml()).hash, h);
  // Not the YAML's own hash: the deck's bytes are in it.
  std::ifstream in(c.yaml(), std::ios::binary);
  const std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(scenario_hash_of_text(yaml), h);

  // One byte each: a letter of the deck's title (the scenario's `name` replaces the title, so
  // the model is the same), a coordinate's last digit in the included file (0.0000 -> 0.0001 mm).
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"two_rates.k", "two-rate"},
                                   {"bar_nodes.k", "0.0000\n"}}) {
    const std::string original = c.read(name);
    std::string changed = original;
    const auto at = changed.find(text);
    ASSERT_NE(at, std::string::npos) << name;
    changed[at + (name == "two_rates.k" ? 0 : 5)] = name == "two_rates.k" ? 'T' : '1';
    c.write(name, changed);
    EXPECT_NE(scenario_hash(c.yaml()), h) << name;
    c.write(name, original);
    EXPECT_EQ(scenario_hash(c.yaml()), h) << name;
  }
  // The same files in another folder (another host's paths): the same hash.
  const DeckCopy other;
  EXPECT_EQ(scenario_hash(other.yaml()), h);
}

TEST(ScenarioDeck, MistakesAreRefusedAtTheirLine) {
  const DeckCopy c;
  c.write("a.yaml", "name: a\nmodel:\n  deck: nope.k\n  units: mm-t-s\n");
  EXPECT_NE(message_of((c.dir / "a.yaml").string())
                .find("a.yaml:3: model.deck: cannot open 'nope.k' (looked for "),
            std::string::npos)
      << message_of((c.dir / "a.yaml").string());

  c.write("b.yaml", "model:\n  deck: two_rates.k\n  units: mm-kg-s\n");
  EXPECT_NE(message_of((c.dir / "b.yaml").string())
                .find("b.yaml:3: model.units: 'mm-kg-s' is not a unit system; fix: one of mm-t-s"),
            std::string::npos)
      << message_of((c.dir / "b.yaml").string());

  c.write("c.yaml", "model:\n  deck: two_rates.k\n  unit: mm-t-s\n");
  EXPECT_NE(message_of((c.dir / "c.yaml").string()).find("c.yaml:3: model.unit: unknown key"),
            std::string::npos)
      << message_of((c.dir / "c.yaml").string());

  c.write("d.yaml", "model: {deck: two_rates.k, units: mm-t-s}\nmaterials: {}\n");
  EXPECT_NE(message_of((c.dir / "d.yaml").string())
                .find("d.yaml:2: materials: the deck named in `model` defines the materials"),
            std::string::npos)
      << message_of((c.dir / "d.yaml").string());

  c.write("e.yaml",
          "model: {deck: two_rates.k, units: mm-t-s}\ndomains:\n  a: {parts: [1]}\n"
          "  b: {parts: [7]}\n");
  EXPECT_NE(message_of((c.dir / "e.yaml").string())
                .find("e.yaml:4: domains.b.parts[0]: unknown part '7' in the deck;"),
            std::string::npos)
      << message_of((c.dir / "e.yaml").string());
  EXPECT_NE(message_of((c.dir / "e.yaml").string()).find("'1 (coarse)', '2 (fine)'"),
            std::string::npos)
      << message_of((c.dir / "e.yaml").string());
  // a PID of 21 digits is unknown, not an overflow (it threw std::out_of_range: exit 4)
  c.write("f.yaml",
          "model: {deck: two_rates.k, units: mm-t-s}\ndomains:\n  a: {parts: [1]}\n"
          "  b: {parts: [123456789012345678901]}\n");
  EXPECT_NE(message_of((c.dir / "f.yaml").string())
                .find("f.yaml:4: domains.b.parts[0]: unknown part '123456789012345678901' in the "
                      "deck;"),
            std::string::npos)
      << message_of((c.dir / "f.yaml").string());

  // A mistake inside the deck keeps the deck's own file:line.
  std::string deck = c.read("two_rates.k");
  deck.replace(deck.find("         1         1         1\n*PART"), 30,
               "         1         1         9");
  c.write("two_rates.k", deck);
  EXPECT_NE(message_of(c.yaml()).find("two_rates.k:"), std::string::npos) << message_of(c.yaml());
  EXPECT_NE(message_of(c.yaml()).find("material 9 is not defined"), std::string::npos)
      << message_of(c.yaml());
}

}  // namespace
}  // namespace crashlink::io
