#include "solver/io/scenario_hash.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string_view>

#include "core/errors.h"
#include "solver/io/scenario_reader.h"
#include "solver/io/yaml_tree.h"

namespace crashlink::io {

namespace {

/// FNV-1a 64 fed piece by piece: the hash of the pieces' concatenation.
struct Fnv1a {
  std::uint64_t h = 14695981039346656037ULL;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 1099511628211ULL;
    }
  }
};

/// Canonical form: M{len:key=value;...} S[value;...] s"len:text" ~ (null). Lengths make it
/// unambiguous whatever the scalars contain. Hashed as it is written (never held whole: a long
/// list would make it as long as the scenario).
void canonical(const YamlTree& tree, YamlTree::Handle n, Fnv1a& out) {
  switch (tree.kind(n)) {
    case YamlTree::Kind::map:
      out.add("M{");
      for (std::size_t i = 0; i < tree.size(n); ++i) {
        canonical(tree, tree.key(n, i), out);
        out.add("=");
        canonical(tree, tree.value(n, i), out);
        out.add(";");
      }
      out.add("}");
      break;
    case YamlTree::Kind::sequence:
      out.add("S[");
      for (std::size_t i = 0; i < tree.size(n); ++i) {
        canonical(tree, tree.item(n, i), out);
        out.add(";");
      }
      out.add("]");
      break;
    case YamlTree::Kind::scalar: {
      const std::string_view s = tree.scalar(n);
      char size[24];
      const auto end = fmt::format_to(size, "s\"{}:", s.size());
      out.add(std::string_view(size, static_cast<std::size_t>(end - size)));
      out.add(s);
      out.add("\"");
      break;
    }
    default:
      out.add("~");
  }
}

}  // namespace

std::string scenario_hash_of_tree(const YamlTree& tree) {
  return finish_scenario_hash(begin_scenario_hash(tree), {});
}

HashOfTree begin_scenario_hash(const YamlTree& tree) {
  Fnv1a h;
  canonical(tree, tree.root(), h);
  return {h.h};
}

std::string finish_scenario_hash(const HashOfTree& tree_hash,
                                 const std::vector<std::string>& files) {
  Fnv1a h{tree_hash.state};
  for (const auto& path : files) {
    // F"size:bytes" per file, streamed (a deck may be hundreds of MB).
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!in || ec)
      throw InputError(path, 0, "(file)", "cannot read the file to hash it; check the path");
    h.add(fmt::format("F\"{}:", size));
    char buf[1 << 16];
    while (in.read(buf, sizeof buf) || in.gcount() > 0)
      h.add(std::string_view(buf, static_cast<std::size_t>(in.gcount())));
    h.add("\"");
  }
  return fmt::format("{:016x}", h.h);
}

namespace {

/// True if the root mapping has a `model` key (a scenario naming a keyword deck).
bool names_a_deck(const YamlTree& tree) {
  const auto root = tree.root();
  if (tree.kind(root) != YamlTree::Kind::map) return false;
  for (std::size_t i = 0; i < tree.size(root); ++i) {
    const auto k = tree.key(root, i);
    if (tree.kind(k) == YamlTree::Kind::scalar && tree.scalar(k) == "model") return true;
  }
  return false;
}

}  // namespace

std::uint64_t fnv1a64(const std::string& bytes) {
  Fnv1a h;
  h.add(bytes);
  return h.h;
}

std::string scenario_hash_of_text(const std::string& yaml_text,
                                  const std::string& name_for_messages) {
  return scenario_hash_of_tree(YamlTree::parse(yaml_text, name_for_messages));
}

std::string scenario_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "(file)", "cannot open the scenario file; check the path");
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const YamlTree tree = YamlTree::parse(in, ec ? 0 : static_cast<std::size_t>(bytes), path);
  if (names_a_deck(tree)) return read_scenario_with_hash(path).hash;
  return scenario_hash_of_tree(tree);
}

}  // namespace crashlink::io
