// Merging coincident nodes through a hash grid (node_merging.h).
#include "solver/model/node_merging.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/errors.h"

namespace crashlink::model {

namespace {

struct Cell {
  std::int64_t i, j, k;
  bool operator==(const Cell&) const = default;
};

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    // Large odd multipliers (Teschner et al. 2003, "Optimized spatial hashing").
    const auto h = static_cast<std::uint64_t>(c.i) * 73856093ULL ^
                   static_cast<std::uint64_t>(c.j) * 19349663ULL ^
                   static_cast<std::uint64_t>(c.k) * 83492791ULL;
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

std::size_t merge_coincident_nodes(Model& m, std::size_t first_new, double tolerance_m) {
  if (!(tolerance_m > 0.0))
    throw ModelError(
        fmt::format("node merging: tolerance {} m must be > 0 (e.g. 1e-6)", tolerance_m));
  const std::size_t n = m.nodes.count();
  CRASHLINK_ASSERT(first_new <= n);
  const auto& x = m.nodes.x0;
  // Cell index of one coordinate. Coordinates beyond 4e18 tolerances (or not finite) share the
  // edge cells: converting them would overflow (found by the scenario fuzz target,
  // docs/fuzzing.md); distances are still checked exactly, so merging stays right.
  auto index = [&](double v) {
    constexpr double kEdge = 4.0e18;
    const double q = std::floor(v / tolerance_m);
    return static_cast<std::int64_t>(q > kEdge ? kEdge : q >= -kEdge ? q : -kEdge);
  };
  auto cell_of = [&](std::size_t node) {
    return Cell{index(x[3 * node]), index(x[3 * node + 1]), index(x[3 * node + 2])};
  };
  std::unordered_map<Cell, std::vector<std::int32_t>, CellHash> grid;
  grid.reserve(first_new);
  for (std::size_t i = 0; i < first_new; ++i)
    grid[cell_of(i)].push_back(static_cast<std::int32_t>(i));

  // new_index[i - first_new]: the index node i ends up at (an old node, or its compacted slot).
  std::vector<std::int32_t> new_index(n - first_new);
  std::size_t kept = first_new, merged = 0;
  const double tol2 = tolerance_m * tolerance_m;
  for (std::size_t i = first_new; i < n; ++i) {
    const Cell c = cell_of(i);
    std::int32_t best = -1;
    double best_d2 = tol2;
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto it = grid.find(Cell{c.i + di, c.j + dj, c.k + dk});
          if (it == grid.end()) continue;
          for (std::int32_t o : it->second) {
            double d2 = 0.0;
            for (std::size_t a = 0; a < 3; ++a) {
              const double d = x[3 * i + a] - x[3 * static_cast<std::size_t>(o) + a];
              d2 += d * d;
            }
            if (d2 <= best_d2) {
              best_d2 = d2;
              best = o;
            }
          }
        }
    if (best >= 0) {
      new_index[i - first_new] = best;
      ++merged;
    } else {
      new_index[i - first_new] = static_cast<std::int32_t>(kept++);
    }
  }
  if (merged == 0) return 0;

  // Compact the new nodes in place (kept slots only move down) and renumber their ids.
  const std::int64_t first_id = m.nodes.id[first_new];
  for (std::size_t i = first_new; i < n; ++i) {
    const auto to = static_cast<std::size_t>(new_index[i - first_new]);
    if (to < first_new) continue;
    m.nodes.id[to] = first_id + static_cast<std::int64_t>(to - first_new);
    for (std::size_t a = 0; a < 3; ++a) m.nodes.x0[3 * to + a] = m.nodes.x0[3 * i + a];
  }
  m.nodes.id.resize(kept);
  m.nodes.x0.resize(3 * kept);
  if (!m.fixed.empty()) m.fixed.resize(kept);
  for (auto& p : m.parts)
    for (auto& c : p.connectivity)
      if (static_cast<std::size_t>(c) >= first_new)
        c = new_index[static_cast<std::size_t>(c) - first_new];
  return merged;
}

}  // namespace crashlink::model
