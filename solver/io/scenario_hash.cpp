#include "solver/io/scenario_hash.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

#include "solver/core/errors.h"

namespace crashlink::io {

namespace {

/// Canonical form: M{len:key=value;...} S[value;...] s"len:text" ~ (null). Lengths make it
/// unambiguous whatever the scalars contain.
void canonical(const YAML::Node& n, std::string& out) {
  switch (n.Type()) {
    case YAML::NodeType::Map:
      out += "M{";
      for (const auto& kv : n) {
        canonical(kv.first, out);
        out += '=';
        canonical(kv.second, out);
        out += ';';
      }
      out += '}';
      break;
    case YAML::NodeType::Sequence:
      out += "S[";
      for (const auto& item : n) {
        canonical(item, out);
        out += ';';
      }
      out += ']';
      break;
    case YAML::NodeType::Scalar:
      out += fmt::format("s\"{}:{}\"", n.Scalar().size(), n.Scalar());
      break;
    default:
      out += '~';
  }
}

}  // namespace

std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string scenario_hash_of_text(const std::string& yaml_text,
                                  const std::string& name_for_messages) {
  YAML::Node doc;
  try {
    doc = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw InputError(name_for_messages, e.mark.is_null() ? 1 : e.mark.line + 1, "(yaml syntax)",
                     e.msg + "; check the indentation and the ':' after each key");
  }
  std::string text;
  canonical(doc, text);
  return fmt::format("{:016x}", fnv1a64(text));
}

std::string scenario_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "(file)", "cannot open the scenario file; check the path");
  std::ostringstream text;
  text << in.rdbuf();
  return scenario_hash_of_text(text.str(), path);
}

}  // namespace crashlink::io
