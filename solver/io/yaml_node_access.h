#pragma once
// Checked access to a parsed YAML tree (yaml_tree.h): every read knows its key path
// ("parts.plate.thickness") and its 1-based line, and every failure throws
// crashlink::InputError("file:line: key: what; fix"). Internal to crashlink::io: include only
// from .cpp files of solver/io.
//
// Line convention: a value's line is the line of the key that introduces it (for a mapping value
// that is the line of "key:", not of its first child); a sequence item's line is its own line.
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/vec3.h"
#include "solver/io/yaml_tree.h"

namespace crashlink::io {

class YamlList;

class YamlNode {
 public:
  /// The document root; `file` names the scenario in messages.
  YamlNode(std::shared_ptr<const YamlTree> tree, const std::string& file);

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  int line() const { return line_; }

  /// Throws InputError(file, line, path, what) — `what` says what is wrong and how to fix it.
  [[noreturn]] void fail(const std::string& what) const;

  bool is_map() const { return kind() == YamlTree::Kind::map; }
  bool is_sequence() const { return kind() == YamlTree::Kind::sequence; }
  bool is_scalar() const { return kind() == YamlTree::Kind::scalar; }

  /// Requires a mapping whose keys are all in `allowed` (no duplicates); an unknown key fails at
  /// its line with the nearest valid key suggested.
  void expect_keys(std::initializer_list<const char*> allowed) const;
  void expect_keys(const std::vector<std::string>& allowed) const;

  bool has(const std::string& key) const;
  /// The value under `key`; fails (at this mapping's line) if it is missing. `hint` completes
  /// the fix, e.g. "the shell thickness in m, e.g. 0.001".
  YamlNode required(const std::string& key, const std::string& hint = "") const;
  std::optional<YamlNode> optional(const std::string& key) const;

  /// Mapping entries in document order; fails if this is not a mapping.
  std::vector<std::pair<std::string, YamlNode>> entries(const std::string& what = "") const;
  /// Sequence items; fails if this is not a sequence.
  std::vector<YamlNode> items(const std::string& what = "") const;
  /// The same items without a YamlNode each until asked (long lists); fails as items().
  YamlList list(const std::string& what = "") const;

  double number() const;         ///< a finite number
  double positive() const;       ///< > 0
  double non_negative() const;   ///< >= 0
  std::int64_t integer() const;  ///< an integer
  int positive_int() const;      ///< an int >= 1
  bool boolean() const;          ///< true/false
  std::string text() const;      ///< a scalar
  /// One of `choices`; the failure lists them and suggests the nearest.
  std::string choice(std::initializer_list<const char*> choices) const;
  std::vector<double> numbers(std::size_t min_count = 0) const;  ///< a sequence of numbers
  Vec3 vec3() const;                                             ///< exactly three numbers

  /// Shorthands for optional keys with a default.
  double number_or(const std::string& key, double fallback) const;
  double non_negative_or(const std::string& key, double fallback) const;
  double positive_or(const std::string& key, double fallback) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  Vec3 vec3_or(const std::string& key, const Vec3& fallback) const;

 private:
  friend class YamlList;
  YamlNode(std::shared_ptr<const YamlTree> tree, YamlTree::Handle node, std::string path,
           std::shared_ptr<const std::string> file, int line);
  YamlNode child(YamlTree::Handle key, YamlTree::Handle value, const std::string& name) const;
  YamlTree::Kind kind() const { return tree_->kind(node_); }
  std::string describe() const;  ///< the value as written, for messages

  std::shared_ptr<const YamlTree> tree_;
  YamlTree::Handle node_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
  int line_ = 1;
};

/// A sequence's items, read one by one: integer(i) and number(i) convert item i as
/// (*this)[i].integer() and .number() do, failing with the same message at the item's line, but
/// build the item's YamlNode (its path "key[i]") only to fail.
class YamlList {
 public:
  explicit YamlList(const YamlNode& sequence) : seq_(sequence) {}
  std::size_t size() const { return seq_.tree_->size(seq_.node_); }
  YamlNode operator[](std::size_t i) const;
  std::int64_t integer(std::size_t i) const;
  double number(std::size_t i) const;

 private:
  YamlNode seq_;
};

/// The candidate closest to `word` by edit distance, or "" if none is close enough to be a
/// plausible typo (distance <= max(2, |word| / 3)).
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

/// "'a', 'b', 'c'" — names for a message.
std::string quoted_list(const std::vector<std::string>& words);

/// " did you mean 'x'?" or "" — ready to append to a message.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace crashlink::io
