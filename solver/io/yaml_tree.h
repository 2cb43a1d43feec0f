#pragma once
// A parsed YAML document in a compact form (for a scenario's long lists). Built
// from yaml-cpp's event parser (YAML::Parser, first document only, as YAML::Load), so the
// structure, the scalars and the line of every node are exactly those YAML::Load would give;
// only the storage differs. yaml-cpp's own node tree costs several hundred bytes per scalar; here
// a sequence whose items are all scalars (a list of ids or of numbers) is stored packed: the
// items' text back to back in one buffer, a 4-byte end offset per item and the items' lines as
// runs (one run for a flow list on one line, or for a block list of one item per line). Every
// other node is a 32-byte record. Aliases share the anchored node, as in yaml-cpp.
//
// Internal to crashlink::io (read through YamlNode, yaml_node_access.h).
#include <cstdint>
#include <deque>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace crashlink::io {

class YamlTree {
 public:
  enum class Kind : std::uint8_t { null, scalar, sequence, map };

  /// A node: `node` indexes the records; `item` is kWhole, or the index of an item of the packed
  /// sequence `node` (a scalar without a record of its own).
  struct Handle {
    std::uint32_t node = 0;
    std::uint32_t item = kWhole;
  };
  static constexpr std::uint32_t kWhole = 0xffffffffu;

  /// Parses the first document of `in` (an empty stream gives a null root without a line).
  /// `size_hint`: the input's size in bytes, to size the text buffer once. Throws
  /// InputError(file, line, "(yaml syntax)", ...) on malformed YAML.
  static YamlTree parse(std::istream& in, std::size_t size_hint, const std::string& file);
  static YamlTree parse(const std::string& text, const std::string& file);

  Handle root() const { return {root_, kWhole}; }
  Kind kind(Handle h) const;
  /// 1-based line of the node's mark; 0 if it has none (the root of an empty document).
  std::uint32_t line(Handle h) const;
  /// The scalar's value (a scalar only).
  std::string_view scalar(Handle h) const;
  /// Items of a sequence, entries of a mapping (0 otherwise).
  std::size_t size(Handle h) const;
  Handle item(Handle sequence, std::size_t i) const;
  Handle key(Handle map, std::size_t i) const;
  Handle value(Handle map, std::size_t i) const;

 private:
  struct Record {
    std::uint64_t begin = 0;  ///< scalar: text offset; packed: first end; else first child
    std::uint64_t text = 0;   ///< packed: the first item's text offset
    std::uint32_t count = 0;  ///< scalar: bytes; sequence: items; map: entries
    std::uint32_t line = 0;   ///< 1-based, 0: no mark
    Kind kind = Kind::null;
    bool packed = false;
  };
  /// Lines of packed items: from global item `item` on, line + step * (index - item).
  struct LineRun {
    std::uint64_t item = 0;
    std::uint32_t line = 0;
    std::uint32_t step = 0;
  };
  friend class YamlTreeBuilder;
  std::uint32_t packed_line(std::uint64_t global_item) const;

  std::string text_;                  ///< every scalar's value, back to back
  std::vector<Record> records_;       ///< every node but the items of packed sequences
  std::vector<std::uint32_t> links_;  ///< children of unpacked sequences and maps (key, value)
  std::deque<std::uint32_t> ends_;    ///< packed items: end offset from the sequence's text
  std::vector<LineRun> runs_;         ///< packed items' lines, by global item index
  std::uint32_t root_ = 0;
};

}  // namespace crashlink::io
