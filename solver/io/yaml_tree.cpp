#include "solver/io/yaml_tree.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <limits>
#include <streambuf>

#include "core/errors.h"

namespace crashlink::io {

/// Receives yaml-cpp's events (in the order NodeBuilder, behind YAML::Load, receives them) and
/// writes the records. A sequence starts packed and stays so while its items are plain scalars
/// without anchors; any other item unpacks it (its items become records) first.
class YamlTreeBuilder final : public YAML::EventHandler {
 public:
  explicit YamlTreeBuilder(YamlTree& t) : t_(t) {}
  bool has_root() const { return has_root_; }

  void OnDocumentStart(const YAML::Mark& /*mark*/) override {}
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    attach(add(Kind::null, mark), anchor);
  }

  void OnAlias(const YAML::Mark& /*mark*/, YAML::anchor_t anchor) override {
    attach(anchors_.at(anchor), YAML::NullAnchor);  // the anchored node itself, as yaml-cpp
  }

  void OnScalar(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                const std::string& value) override {
    if (!open_.empty() && open_.back().packed && anchor == YAML::NullAnchor &&
        append_item(mark, value))
      return;
    const std::uint32_t r = add(Kind::scalar, mark);
    t_.records_[r].begin = t_.text_.size();
    t_.records_[r].count = checked_u32(value.size());
    t_.text_ += value;
    attach(r, anchor);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value /*style*/) override {
    open(add(Kind::sequence, mark), anchor, true);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value /*style*/) override {
    open(add(Kind::map, mark), anchor, false);
  }
  void OnMapEnd() override { close(); }

 private:
  using Kind = YamlTree::Kind;
  struct Open {
    std::uint32_t node = 0;
    bool packed = false;
    std::uint64_t first_end = 0;  ///< packed: index of its first item in ends_
    std::uint64_t text = 0;       ///< packed: offset of its first item's text
    std::vector<std::uint32_t> children;
  };

  static std::uint32_t checked_u32(std::uint64_t n) {
    if (n >= YamlTree::kWhole)
      throw InputError("a YAML scalar, list or mapping above 4 Gi bytes or items");
    return static_cast<std::uint32_t>(n);
  }

  std::uint32_t add(Kind kind, const YAML::Mark& mark) {
    YamlTree::Record r;
    r.kind = kind;
    r.line = mark.is_null() ? 0 : static_cast<std::uint32_t>(mark.line + 1);
    t_.records_.push_back(r);
    return checked_u32(t_.records_.size() - 1);
  }

  void attach(std::uint32_t r, YAML::anchor_t anchor) {
    if (anchor != YAML::NullAnchor) {
      if (anchors_.size() <= anchor) anchors_.resize(anchor + 1, 0);
      anchors_[anchor] = r;
    }
    if (open_.empty()) {
      if (!has_root_) t_.root_ = r;
      has_root_ = true;
      return;
    }
    Open& top = open_.back();
    if (top.packed) unpack(top);
    top.children.push_back(r);
  }

  void open(std::uint32_t r, YAML::anchor_t anchor, bool sequence) {
    attach(r, anchor);
    Open o;
    o.node = r;
    o.packed = sequence;
    o.first_end = t_.ends_.size();
    o.text = t_.text_.size();
    open_.push_back(std::move(o));
  }

  void close() {
    Open& o = open_.back();
    YamlTree::Record& r = t_.records_[o.node];
    if (o.packed) {
      r.packed = true;
      r.begin = o.first_end;
      r.text = o.text;
      r.count = checked_u32(t_.ends_.size() - o.first_end);
    } else {
      r.begin = t_.links_.size();
      r.count = checked_u32(r.kind == Kind::map ? o.children.size() / 2 : o.children.size());
      t_.links_.insert(t_.links_.end(), o.children.begin(), o.children.end());
    }
    open_.pop_back();
  }

  /// Appends a scalar item to the packed sequence on top; false if it cannot be packed.
  bool append_item(const YAML::Mark& mark, const std::string& value) {
    Open& o = open_.back();
    const std::uint64_t end = t_.text_.size() + value.size() - o.text;
    const std::uint64_t g = t_.ends_.size();
    if (end >= YamlTree::kWhole || g - o.first_end + 1 >= YamlTree::kWhole) {
      unpack(o);
      return false;
    }
    t_.text_ += value;
    t_.ends_.push_back(static_cast<std::uint32_t>(end));
    const auto line = static_cast<std::uint32_t>(mark.line + 1);
    if (g == o.first_end) {
      t_.runs_.push_back({g, line, 0});
      return true;
    }
    YamlTree::LineRun& run = t_.runs_.back();
    if (line == run.line + run.step * (g - run.item)) return true;
    if (g - run.item == 1 && run.step == 0 && line == run.line + 1) {
      run.step = 1;  // a block list: one item per line
      return true;
    }
    t_.runs_.push_back({g, line, 0});
    return true;
  }

  /// Makes the packed items of `o` records of their own (their text stays where it is).
  void unpack(Open& o) {
    const std::uint64_t n = t_.ends_.size() - o.first_end;
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::uint64_t from = k == 0 ? 0 : t_.ends_[o.first_end + k - 1];
      YamlTree::Record r;
      r.kind = Kind::scalar;
      r.begin = o.text + from;
      r.count = static_cast<std::uint32_t>(t_.ends_[o.first_end + k] - from);
      r.line = t_.packed_line(o.first_end + k);
      t_.records_.push_back(r);
      o.children.push_back(checked_u32(t_.records_.size() - 1));
    }
    t_.ends_.resize(o.first_end);
    while (!t_.runs_.empty() && t_.runs_.back().item >= o.first_end) t_.runs_.pop_back();
    o.packed = false;
  }

  YamlTree& t_;
  std::vector<Open> open_;
  std::vector<std::uint32_t> anchors_;  ///< record of each anchor (yaml-cpp numbers them 1, 2, ...)
  bool has_root_ = false;
};

namespace {

/// Reads a string in place (std::istringstream would copy it).
class StringViewBuffer : public std::streambuf {
 public:
  explicit StringViewBuffer(const std::string& s) {
    char* p = const_cast<char*>(s.data());  // only read: get area
    setg(p, p, p + s.size());
  }
};

}  // namespace

YamlTree YamlTree::parse(std::istream& in, std::size_t size_hint, const std::string& file) {
  YamlTree t;
  t.text_.reserve(size_hint);  // the values are at most the input (pages touched as written)
  YamlTreeBuilder builder(t);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(builder);
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 1 : e.mark.line + 1, "(yaml syntax)",
                     e.msg + "; check the indentation and the ':' after each key");
  }
  if (!builder.has_root()) {  // empty document: YAML::Load gives a null node without a mark
    t.records_.push_back(Record{});
    t.root_ = static_cast<std::uint32_t>(t.records_.size() - 1);
  }
  return t;
}

YamlTree YamlTree::parse(const std::string& text, const std::string& file) {
  StringViewBuffer buffer(text);
  std::istream in(&buffer);
  return parse(in, text.size(), file);
}

std::uint32_t YamlTree::packed_line(std::uint64_t global_item) const {
  auto it = std::upper_bound(runs_.begin(), runs_.end(), global_item,
                             [](std::uint64_t g, const LineRun& r) { return g < r.item; });
  const LineRun& run = *(it - 1);  // the sequence's first item always starts a run
  return run.line + run.step * static_cast<std::uint32_t>(global_item - run.item);
}

YamlTree::Kind YamlTree::kind(Handle h) const {
  return h.item != kWhole ? Kind::scalar : records_[h.node].kind;
}

std::uint32_t YamlTree::line(Handle h) const {
  const Record& r = records_[h.node];
  return h.item != kWhole ? packed_line(r.begin + h.item) : r.line;
}

std::string_view YamlTree::scalar(Handle h) const {
  const Record& r = records_[h.node];
  if (h.item != kWhole) {
    const std::uint64_t from = h.item == 0 ? 0 : ends_[r.begin + h.item - 1];
    return std::string_view(text_).substr(r.text + from, ends_[r.begin + h.item] - from);
  }
  if (r.kind != Kind::scalar) return {};
  return std::string_view(text_).substr(r.begin, r.count);
}

std::size_t YamlTree::size(Handle h) const {
  if (h.item != kWhole) return 0;
  const Record& r = records_[h.node];
  return r.kind == Kind::sequence || r.kind == Kind::map ? r.count : 0;
}

YamlTree::Handle YamlTree::item(Handle sequence, std::size_t i) const {
  const Record& r = records_[sequence.node];
  if (r.packed) return {sequence.node, static_cast<std::uint32_t>(i)};
  return {links_[r.begin + i], kWhole};
}

YamlTree::Handle YamlTree::key(Handle map, std::size_t i) const {
  return {links_[records_[map.node].begin + 2 * i], kWhole};
}

YamlTree::Handle YamlTree::value(Handle map, std::size_t i) const {
  return {links_[records_[map.node].begin + 2 * i + 1], kWhole};
}

}  // namespace crashlink::io
