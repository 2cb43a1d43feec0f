#include "solver/io/scenario_hash.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string_view>

#include "solver/core/errors.h"
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
  Fnv1a h;
  canonical(tree, tree.root(), h);
  return fmt::format("{:016x}", h.h);
}

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
  return scenario_hash_of_tree(YamlTree::parse(in, ec ? 0 : static_cast<std::size_t>(bytes), path));
}

}  // namespace crashlink::io
