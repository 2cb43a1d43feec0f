#pragma once
// The few nodes that carry a sparse nodal array's non-zeros (the coupling loads, the contact
// forces): the passes over all nodes leave the array out and visit these apart.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/errors.h"

namespace crashlink::integration {

/// A set of node indices: insert in O(1), walk in insertion order, or in index order once sorted.
class NodeSet {
 public:
  /// Empty, for nodes [0, n).
  void reset(std::size_t n) {
    mark_.assign(n, 0);
    list_.clear();
  }
  void insert(std::size_t i) {
    CRASHLINK_ASSERT(i < mark_.size());
    if (mark_[i]) return;
    mark_[i] = 1;
    list_.push_back(static_cast<std::int32_t>(i));
  }
  /// Puts the nodes in index order (once, after the inserts).
  void sort() {
    if (!std::is_sorted(list_.begin(), list_.end())) std::sort(list_.begin(), list_.end());
  }
  void clear() {
    for (const auto i : list_) mark_[static_cast<std::size_t>(i)] = 0;
    list_.clear();
  }
  const std::vector<std::int32_t>& nodes() const { return list_; }
  bool empty() const { return list_.empty(); }

 private:
  std::vector<std::uint8_t> mark_;  // [n]
  std::vector<std::int32_t> list_;
};

/// sum f[k] d[k] over the dofs of `nodes` (3 each), in their order: the sum over every dof when
/// f is zero elsewhere, the same bits for any thread count (one thread, a fixed order). Not the
/// bits of a sum over all dofs in tiles: its rounding (and the compiler's contraction into FMAs)
/// differs in the last place [J for f in N and d in m]. d: an array, or d(k) for a value computed
/// where it is read (Solver::du_at).
template <class D>
double sparse_dot(const std::vector<std::int32_t>& nodes, const double* f, const D& d) {
  double s = 0.0;
  for (const auto node : nodes)
    for (std::size_t k = 3 * static_cast<std::size_t>(node);
         k < 3 * static_cast<std::size_t>(node) + 3; ++k) {
      if constexpr (std::is_invocable_v<const D&, std::size_t>)
        s += f[k] * d(k);
      else
        s += f[k] * d[k];
    }
  return s;
}

}  // namespace crashlink::integration
