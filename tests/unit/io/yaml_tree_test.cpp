// The compact YAML tree (solver/io/yaml_tree.h): lists of scalars are stored packed, yet every
// item keeps its line, mixed lists and aliases read as yaml-cpp's tree does; and the reader's
// messages about one item of a long list name that item and its line.
#include "solver/io/yaml_tree.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::io {
namespace {

using Kind = YamlTree::Kind;

/// The value of the top-level key `key`.
YamlTree::Handle top(const YamlTree& t, const std::string& key) {
  for (std::size_t i = 0; i < t.size(t.root()); ++i)
    if (t.scalar(t.key(t.root(), i)) == key) return t.value(t.root(), i);
  ADD_FAILURE() << "no key " << key;
  return t.root();
}

std::vector<std::uint32_t> item_lines(const YamlTree& t, YamlTree::Handle seq) {
  std::vector<std::uint32_t> lines;
  for (std::size_t i = 0; i < t.size(seq); ++i) lines.push_back(t.line(t.item(seq, i)));
  return lines;
}

TEST(YamlTree, PackedListsKeepEachItemsLine) {
  const auto t = YamlTree::parse(
      "flow: [1, 2,\n  3,\n\n  4]\nblock:\n  - 5\n  - 6\n  # a comment\n  - 7\n  - 8\n", "t.yaml");
  const auto flow = top(t, "flow");
  ASSERT_EQ(t.kind(flow), Kind::sequence);
  EXPECT_EQ(item_lines(t, flow), (std::vector<std::uint32_t>{1, 1, 2, 4}));
  EXPECT_EQ(t.scalar(t.item(flow, 3)), "4");
  const auto block = top(t, "block");
  EXPECT_EQ(item_lines(t, block), (std::vector<std::uint32_t>{6, 7, 9, 10}));
  EXPECT_EQ(t.scalar(t.item(block, 2)), "7");
}

TEST(YamlTree, MixedListsNullsAndQuotesReadAsYamlCpp) {
  const auto t = YamlTree::parse("a: [1, 'x y', [2, 3], ~, {k: v}]\nb:\n", "t.yaml");
  const auto a = top(t, "a");
  ASSERT_EQ(t.size(a), 5u);
  EXPECT_EQ(t.scalar(t.item(a, 0)), "1");
  EXPECT_EQ(t.scalar(t.item(a, 1)), "x y");
  EXPECT_EQ(t.kind(t.item(a, 2)), Kind::sequence);
  EXPECT_EQ(t.scalar(t.item(t.item(a, 2), 1)), "3");
  EXPECT_EQ(t.kind(t.item(a, 3)), Kind::null);
  EXPECT_EQ(t.kind(t.item(a, 4)), Kind::map);
  EXPECT_EQ(t.line(t.item(a, 0)), 1u);
  EXPECT_EQ(t.kind(top(t, "b")), Kind::null);
}

TEST(YamlTree, AliasesShareTheAnchoredNode) {
  const auto t = YamlTree::parse("a: &l [1, 2]\nb: [&s 3, 4]\nc: *l\nd: *s\n", "t.yaml");
  EXPECT_EQ(top(t, "c").node, top(t, "a").node);
  EXPECT_EQ(t.scalar(t.item(top(t, "c"), 1)), "2");
  EXPECT_EQ(t.scalar(top(t, "d")), "3");
  EXPECT_EQ(t.line(top(t, "d")), 2u);  // the anchored node's line, as yaml-cpp's Mark
}

TEST(YamlTree, EmptyDocumentAndSyntaxErrors) {
  const auto t = YamlTree::parse(std::string(), "t.yaml");
  EXPECT_EQ(t.kind(t.root()), Kind::null);
  EXPECT_EQ(t.line(t.root()), 0u);
  try {
    (void)YamlTree::parse("a: [1, 2\nb: 3\n", "t.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "(yaml syntax)");
  }
}

TEST(YamlTree, HashIsTheCanonicalTextsFnv) {
  // M{s"1:a"=S[s"1:1";s"1:2";];} written out and hashed whole.
  EXPECT_EQ(scenario_hash_of_text("a: [1, 2]\n"),
            fmt::format("{:016x}", fnv1a64("M{s\"1:a\"=S[s\"1:1\";s\"1:2\";];}")));
  EXPECT_EQ(scenario_hash_of_text("a: [1, ~]\n"),
            fmt::format("{:016x}", fnv1a64("M{s\"1:a\"=S[s\"1:1\";~;];}")));
}

TEST(YamlTree, ReadWithHashIsReadAndHash) {
  const std::string path = std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml";
  const auto both = read_scenario_with_hash(path);
  EXPECT_EQ(both.hash, scenario_hash(path));
  const auto model = read_scenario(path);
  EXPECT_EQ(both.model.nodes.x0, model.nodes.x0);
  EXPECT_EQ(both.model.fixed, model.fixed);
  ASSERT_EQ(both.model.parts.size(), model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    EXPECT_EQ(both.model.parts[p].connectivity, model.parts[p].connectivity);
}

const std::string kBox = R"(name: t
controls: {end_time: 1.0e-3}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  block:
    material: steel
    mesh: {generator: box, size: [1.0, 1.0, 1.0], divisions: [1, 1, 1]}
)";

void expect_error_at(const std::string& yaml, int line, const std::string& key,
                     const std::string& fragment) {
  try {
    (void)parse_scenario(yaml, "bad.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(YamlTree, ReaderNamesTheBadItemOfAListAndItsLine) {
  expect_error_at(kBox + "node_sets:\n  s: {nodes: [1, 2,\n    3, 99]}\n", 11,
                  "node_sets.s.nodes[3]", "node id 99 is not in the model");
  expect_error_at(kBox + "node_sets:\n  s:\n    nodes:\n      - 1\n      - x\n", 13,
                  "node_sets.s.nodes[1]", "expected an integer, got 'x'");
  expect_error_at(kBox + "node_sets:\n  s: {nodes: [1, [2]]}\n", 10, "node_sets.s.nodes[1]",
                  "expected an integer, got a list");
  expect_error_at(kBox +
                      "prescribed_velocity:\n  - nodes: {part: block}\n    dof: x\n"
                      "    curve:\n      t: [0.0,\n          .inf]\n      v: [0.0, 1.0]\n",
                  14, "prescribed_velocity[0].curve.t[1]", "expected a finite number, got '.inf'");
  expect_error_at(kBox + "node_sets:\n  s: {nodes: []}\n", 10, "node_sets.s.nodes",
                  "empty node list");
}

TEST(YamlTree, IdListsReadAsTheirSortedUniqueNodes) {
  const auto m = parse_scenario(
      kBox + "node_sets:\n  s: {nodes: [8, 0x2, 1, 8, 010]}\nboundary:\n  - {nodes: s, fix: [x]}\n",
      "ok.yaml");
  // 0x2 and 010 read as yaml-cpp reads integers: 2 and 8.
  EXPECT_EQ(m.fixed, (std::vector<std::uint8_t>{1, 1, 0, 0, 0, 0, 0, 1}));
}

}  // namespace
}  // namespace crashlink::io
