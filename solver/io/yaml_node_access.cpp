#include "solver/io/yaml_node_access.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "solver/io/yaml_scalar.h"

namespace crashlink::io {

namespace {

int line_of(const YamlTree& tree, YamlTree::Handle h, int fallback) {
  const std::uint32_t line = tree.line(h);
  return line == 0 ? fallback : static_cast<int>(line);
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Levenshtein distance, one row of the dynamic-programming table.
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  return best_d <= limit ? best : std::string();
}

std::string quoted_list(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "'" : ", '") + w + "'";
  return s;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string n = nearest_word(word, candidates);
  return n.empty() ? std::string() : " did you mean '" + n + "'?";
}

YamlNode::YamlNode(std::shared_ptr<const YamlTree> tree, const std::string& file)
    : tree_(std::move(tree)),
      node_(tree_->root()),
      path_(),
      file_(std::make_shared<const std::string>(file)),
      line_(line_of(*tree_, node_, 1)) {}

YamlNode::YamlNode(std::shared_ptr<const YamlTree> tree, YamlTree::Handle node, std::string path,
                   std::shared_ptr<const std::string> file, int line)
    : tree_(std::move(tree)),
      node_(node),
      path_(std::move(path)),
      file_(std::move(file)),
      line_(line) {}

YamlNode YamlNode::child(YamlTree::Handle key, YamlTree::Handle value,
                         const std::string& name) const {
  const int line = line_of(*tree_, key, line_of(*tree_, value, line_));
  return YamlNode(tree_, value, path_.empty() ? name : path_ + "." + name, file_, line);
}

void YamlNode::fail(const std::string& what) const {
  throw InputError(*file_, line_, path_.empty() ? std::string("(top level)") : path_, what);
}

std::string YamlNode::describe() const {
  switch (kind()) {
    case YamlTree::Kind::map:
      return "a mapping";
    case YamlTree::Kind::sequence:
      return "a list";
    case YamlTree::Kind::scalar: {
      std::string quoted = "'";  // (not "'" + ... + "'": g++ 12 warns -Wrestrict on it)
      quoted += tree_->scalar(node_);
      return quoted += "'";
    }
    default:
      return "nothing";
  }
}

void YamlNode::expect_keys(std::initializer_list<const char*> allowed) const {
  expect_keys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void YamlNode::expect_keys(const std::vector<std::string>& allowed) const {
  const auto all = entries();
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& [key, value] = all[i];
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      const std::string guess = did_you_mean(key, allowed);
      value.fail("unknown key;" + (guess.empty() ? std::string() : guess) +
                 " valid keys here: " + quoted_list(allowed));
    }
    for (std::size_t j = 0; j < i; ++j)
      if (all[j].first == key)
        value.fail(
            fmt::format("key given twice (also on line {}); keep one", all[j].second.line()));
  }
}

std::vector<std::pair<std::string, YamlNode>> YamlNode::entries(const std::string& what) const {
  if (!is_map())
    fail("expected a mapping (key: value lines)" + (what.empty() ? "" : " of " + what) + ", got " +
         describe());
  std::vector<std::pair<std::string, YamlNode>> out;
  for (std::size_t i = 0; i < tree_->size(node_); ++i) {
    const YamlTree::Handle key = tree_->key(node_, i);
    if (tree_->kind(key) != YamlTree::Kind::scalar)
      YamlNode(tree_, key, path_, file_, line_of(*tree_, key, line_))
          .fail("a key must be a plain word, not a list or mapping");
    std::string name(tree_->scalar(key));
    YamlNode value = child(key, tree_->value(node_, i), name);
    out.emplace_back(std::move(name), std::move(value));
  }
  return out;
}

std::vector<YamlNode> YamlNode::items(const std::string& what) const {
  const YamlList all = list(what);
  std::vector<YamlNode> out;
  out.reserve(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) out.push_back(all[i]);
  return out;
}

YamlList YamlNode::list(const std::string& what) const {
  if (!is_sequence())
    fail("expected a list" + (what.empty() ? "" : " of " + what) + ", got " + describe() +
         "; write [a, b, ...] or one '- item' per line");
  return YamlList(*this);
}

YamlNode YamlList::operator[](std::size_t i) const {
  const YamlTree& tree = *seq_.tree_;
  const YamlTree::Handle item = tree.item(seq_.node_, i);
  return YamlNode(seq_.tree_, item, fmt::format("{}[{}]", seq_.path_, i), seq_.file_,
                  line_of(tree, item, seq_.line_));
}

std::int64_t YamlList::integer(std::size_t i) const {
  const YamlTree& tree = *seq_.tree_;
  const YamlTree::Handle item = tree.item(seq_.node_, i);
  std::int64_t v = 0;
  if (tree.kind(item) == YamlTree::Kind::scalar && scalar_to_int64(tree.scalar(item), v)) return v;
  return (*this)[i].integer();  // fails with the item's path and line
}

double YamlList::number(std::size_t i) const {
  const YamlTree& tree = *seq_.tree_;
  const YamlTree::Handle item = tree.item(seq_.node_, i);
  double v = 0.0;
  if (tree.kind(item) == YamlTree::Kind::scalar && scalar_to_double(tree.scalar(item), v) &&
      std::isfinite(v))
    return v;
  return (*this)[i].number();  // fails with the item's path and line
}

bool YamlNode::has(const std::string& key) const {
  return optional(key).has_value();
}

std::optional<YamlNode> YamlNode::optional(const std::string& key) const {
  if (!is_map()) fail("expected a mapping (key: value lines), got " + describe());
  for (std::size_t i = 0; i < tree_->size(node_); ++i) {
    const YamlTree::Handle k = tree_->key(node_, i);
    if (tree_->kind(k) == YamlTree::Kind::scalar && tree_->scalar(k) == key)
      return child(k, tree_->value(node_, i), key);
  }
  return std::nullopt;
}

YamlNode YamlNode::required(const std::string& key, const std::string& hint) const {
  auto v = optional(key);
  if (!v) {
    const std::string full = path_.empty() ? key : path_ + "." + key;
    throw InputError(*file_, line_, full,
                     "required key missing; add '" + key + ": ...'" +
                         (path_.empty() ? " at the top level" : " under '" + path_ + "'") +
                         (hint.empty() ? "" : " (" + hint + ")"));
  }
  return *v;
}

double YamlNode::number() const {
  double v = 0.0;
  if (!is_scalar() || !scalar_to_double(tree_->scalar(node_), v))
    fail("expected a number, got " + describe() +
         "; write a plain number in SI units (e.g. 0.001)");
  if (!std::isfinite(v)) fail("expected a finite number, got " + describe());
  return v;
}

double YamlNode::positive() const {
  const double v = number();
  if (!(v > 0.0)) fail(fmt::format("must be > 0, got {}; give a positive value in SI units", v));
  return v;
}

double YamlNode::non_negative() const {
  const double v = number();
  if (v < 0.0) fail(fmt::format("must be >= 0, got {}", v));
  return v;
}

std::int64_t YamlNode::integer() const {
  std::int64_t v = 0;
  if (!is_scalar() || !scalar_to_int64(tree_->scalar(node_), v))
    fail("expected an integer, got " + describe());
  return v;
}

int YamlNode::positive_int() const {
  const std::int64_t v = integer();
  if (v < 1 || v > std::numeric_limits<int>::max())
    fail(fmt::format("must be an integer >= 1, got {}", v));
  return static_cast<int>(v);
}

bool YamlNode::boolean() const {
  bool v = false;
  if (!is_scalar() || !scalar_to_bool(tree_->scalar(node_), v))
    fail("expected true or false, got " + describe());
  return v;
}

std::string YamlNode::text() const {
  if (!is_scalar()) fail("expected a word or text, got " + describe());
  return std::string(tree_->scalar(node_));
}

std::string YamlNode::choice(std::initializer_list<const char*> choices) const {
  const std::string v = text();
  const std::vector<std::string> all(choices.begin(), choices.end());
  if (std::find(all.begin(), all.end(), v) == all.end())
    fail("'" + v + "' is not one of " + quoted_list(all) + ";" + did_you_mean(v, all));
  return v;
}

std::vector<double> YamlNode::numbers(std::size_t min_count) const {
  const YamlList all = list("numbers");
  std::vector<double> out;
  out.reserve(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) out.push_back(all.number(i));
  if (out.size() < min_count)
    fail(fmt::format("expected at least {} numbers, got {}", min_count, out.size()));
  return out;
}

Vec3 YamlNode::vec3() const {
  const auto all = items("3 numbers [x, y, z]");
  if (all.size() != 3) fail(fmt::format("expected 3 numbers [x, y, z], got {}", all.size()));
  return {all[0].number(), all[1].number(), all[2].number()};
}

double YamlNode::number_or(const std::string& key, double fallback) const {
  const auto v = optional(key);
  return v ? v->number() : fallback;
}

double YamlNode::non_negative_or(const std::string& key, double fallback) const {
  const auto v = optional(key);
  return v ? v->non_negative() : fallback;
}

double YamlNode::positive_or(const std::string& key, double fallback) const {
  const auto v = optional(key);
  return v ? v->positive() : fallback;
}

bool YamlNode::boolean_or(const std::string& key, bool fallback) const {
  const auto v = optional(key);
  return v ? v->boolean() : fallback;
}

Vec3 YamlNode::vec3_or(const std::string& key, const Vec3& fallback) const {
  const auto v = optional(key);
  return v ? v->vec3() : fallback;
}

}  // namespace crashlink::io
