// Node selections and the `node_sets` section (docs/scenario-format.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "core/errors.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io::detail {

namespace {

/// Bounding box [lo, hi] of the nodes `sel` (all nodes if empty pointer).
std::pair<Vec3, Vec3> bounds(const model::Model& m, const std::vector<std::int32_t>* sel) {
  Vec3 lo{}, hi{};
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  auto add = [&](std::size_t i) {
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], m.nodes.x0[3 * i + a]);
      hi[a] = std::max(hi[a], m.nodes.x0[3 * i + a]);
    }
  };
  if (sel) {
    for (auto i : *sel) add(static_cast<std::size_t>(i));
  } else {
    for (std::size_t i = 0; i < m.nodes.count(); ++i) add(i);
  }
  return {lo, hi};
}

/// Model::node_index (first node with the id, -1 if none) in constant time: it scans every node,
/// so a list of ids would cost ids x nodes. A table over [lowest, highest id] when the ids are
/// that dense (generated ids run 1, 2, ...), else a hash map.
class NodeIdIndex {
 public:
  explicit NodeIdIndex(const model::Model& m) {
    const auto& ids = m.nodes.id;
    if (ids.empty()) return;
    const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
    const auto span = static_cast<std::uint64_t>(*hi - *lo);
    if (span <= 4 * static_cast<std::uint64_t>(ids.size()) + 1024) {
      lowest_ = *lo;
      table_.assign(span + 1, -1);
      for (std::size_t i = ids.size(); i-- > 0;)
        table_[static_cast<std::size_t>(ids[i] - lowest_)] = static_cast<int>(i);
    } else {
      for (std::size_t i = ids.size(); i-- > 0;) map_[ids[i]] = static_cast<int>(i);
    }
  }
  int operator()(std::int64_t id) const {
    if (!table_.empty()) {
      if (id < lowest_ || static_cast<std::uint64_t>(id - lowest_) >= table_.size()) return -1;
      return table_[static_cast<std::size_t>(id - lowest_)];
    }
    const auto it = map_.find(id);
    return it == map_.end() ? -1 : it->second;
  }

 private:
  std::int64_t lowest_ = 0;
  std::vector<int> table_;
  std::unordered_map<std::int64_t, int> map_;
};

std::string format_box(const std::pair<Vec3, Vec3>& b) {
  return fmt::format("min [{:g}, {:g}, {:g}], max [{:g}, {:g}, {:g}]", b.first[0], b.first[1],
                     b.first[2], b.second[0], b.second[1], b.second[2]);
}

}  // namespace

int read_part_reference(const YamlNode& ref, const ScenarioBuild& b) {
  const std::string name = ref.text();
  int p = b.model.part_index(name);
  if (p < 0 && !b.deck_part_ids.empty() && !name.empty() && name.size() <= 18 &&
      name.find_first_not_of("0123456789") == std::string::npos) {
    // A deck's part by its *PART PID (a title made of digits is matched first, above; more
    // than 18 digits is no PID: unknown below, not an overflow).
    const auto it = std::find(b.deck_part_ids.begin(), b.deck_part_ids.end(),
                              static_cast<std::int64_t>(std::stoll(name)));
    if (it != b.deck_part_ids.end()) p = static_cast<int>(it - b.deck_part_ids.begin());
  }
  if (p < 0) {
    if (!b.deck_part_ids.empty()) {
      std::vector<std::string> listed;
      for (std::size_t i = 0; i < b.deck_part_ids.size(); ++i)
        listed.push_back(fmt::format("{} ({})", b.deck_part_ids[i], b.model.parts[i].name));
      ref.fail("unknown part '" + name + "' in the deck;" + did_you_mean(name, b.part_names()) +
               " give a *PART PID or title; parts with elements: " + quoted_list(listed));
    }
    ref.fail("unknown part '" + name + "';" + did_you_mean(name, b.part_names()) +
             " parts defined: " + quoted_list(b.part_names()));
  }
  return p;
}

std::vector<std::int32_t> read_selection(const YamlNode& sel, const ScenarioBuild& b) {
  sel.expect_keys({"part", "box", "nodes"});
  const model::Model& m = b.model;
  if (auto ids = sel.optional("nodes")) {
    for (const char* k : {"part", "box"})
      if (auto v = sel.optional(k))
        v->fail("an explicit 'nodes' list cannot be combined with 'part' or 'box'; use one");
    // A list may hold millions of ids: each is marked on the model's nodes,
    // which gives the sorted unique indices without a copy of the list.
    const YamlList list = ids->list("node ids");
    const NodeIdIndex index_of(m);
    std::vector<std::uint8_t> listed(m.nodes.count(), 0);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::int64_t id = list.integer(k);
      const int i = index_of(id);
      if (i < 0)
        list[k].fail(
            fmt::format("node id {} is not in the model (ids run from {} to {} after mesh "
                        "generation; see docs/scenario-format.md, 'Numbering')",
                        id, m.nodes.id.empty() ? 0 : m.nodes.id.front(),
                        m.nodes.id.empty() ? 0 : m.nodes.id.back()));
      listed[static_cast<std::size_t>(i)] = 1;
    }
    if (list.size() == 0) ids->fail("empty node list; give at least one node id");
    std::vector<std::int32_t> out;
    for (std::size_t i = 0; i < listed.size(); ++i)
      if (listed[i]) out.push_back(static_cast<std::int32_t>(i));
    return out;
  }
  const auto part = sel.optional("part");
  const auto box = sel.optional("box");
  if (!part && !box)
    sel.fail(
        "a selection needs 'part: name', 'box: {min: [..], max: [..]}' (or both), or "
        "'nodes: [ids]'");
  std::vector<std::int32_t> candidates;
  if (part) {
    candidates = b.part_nodes(read_part_reference(*part, b));
  } else {
    candidates.resize(m.nodes.count());
    for (std::size_t i = 0; i < candidates.size(); ++i)
      candidates[i] = static_cast<std::int32_t>(i);
  }
  if (!box) return candidates;  // a part always has nodes

  box->expect_keys({"min", "max"});
  const auto min_node = box->required("min", "[x, y, z] in m");
  const Vec3 lo = min_node.vec3();
  const Vec3 hi = box->required("max", "[x, y, z] in m").vec3();
  for (std::size_t a = 0; a < 3; ++a)
    if (lo[a] > hi[a])
      min_node.fail(
          fmt::format("min[{}] = {} is above max[{}] = {}; swap them", a, lo[a], a, hi[a]));
  // Inclusive bounds, widened by 1e-9 of the model's size so nodes exactly on a face are in.
  const auto all = bounds(m, nullptr);
  const double eps = 1e-9 * (norm(all.second - all.first) + 1.0);
  std::vector<std::int32_t> out;
  for (auto i : candidates) {
    const double* x = &m.nodes.x0[3 * static_cast<std::size_t>(i)];
    bool inside = true;
    for (std::size_t a = 0; a < 3; ++a)
      inside = inside && x[a] >= lo[a] - eps && x[a] <= hi[a] + eps;
    if (inside) out.push_back(i);
  }
  if (out.empty())
    box->fail("selects no node; the " + std::string(part ? "part's" : "model's") + " nodes span " +
              format_box(bounds(m, &candidates)) + " [m]; widen the box");
  return out;
}

std::vector<std::int32_t> read_node_reference(const YamlNode& ref, const ScenarioBuild& b) {
  if (ref.is_map()) return read_selection(ref, b);
  const std::string name = ref.text();
  const auto it = b.node_sets.find(name);
  if (it == b.node_sets.end())
    ref.fail("unknown node set '" + name + "';" + did_you_mean(name, b.node_set_names()) +
             " define it under 'node_sets' or write a selection {part, box} here" +
             (b.node_sets.empty() ? "" : " (defined: " + quoted_list(b.node_set_names()) + ")"));
  return it->second;
}

void read_node_sets(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& [name, sel] : section.entries("node sets (name: {part, box} or {nodes})")) {
    if (!sel.is_sequence()) {
      b.node_sets[name] = read_selection(sel, b);
      continue;
    }
    // A list of selections: their union.
    std::vector<std::int32_t> all;
    for (const auto& item : sel.items("selections")) {
      const auto one = read_selection(item, b);
      all.insert(all.end(), one.begin(), one.end());
    }
    if (all.empty()) sel.fail("empty list; give at least one selection {part, box}");
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    b.node_sets[name] = std::move(all);
  }
}

}  // namespace crashlink::io::detail
