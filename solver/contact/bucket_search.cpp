#include "solver/contact/bucket_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crashlink::contact {

namespace {

struct Box {
  double lo[3], hi[3];
};

/// Bounding box of segment i inflated by its reach.
Box segment_box(const SearchInput& in, std::size_t i) {
  Box b{};
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = std::numeric_limits<double>::infinity();
    b.hi[d] = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t a = 0; a < 4; ++a) {
    const double* p = in.x + 3 * static_cast<std::size_t>(in.seg_nodes[4 * i + a]);
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(b.lo[d], p[d]);
      b.hi[d] = std::max(b.hi[d], p[d]);
    }
  }
  for (int d = 0; d < 3; ++d) {
    b.lo[d] -= in.reach[i];
    b.hi[d] += in.reach[i];
  }
  return b;
}

bool inside(const Box& b, const double* p) {
  return p[0] >= b.lo[0] && p[0] <= b.hi[0] && p[1] >= b.lo[1] && p[1] <= b.hi[1] &&
         p[2] >= b.lo[2] && p[2] <= b.hi[2];
}

/// Counting sort of (slave, segment) pairs by slave position, stable (segments stay increasing).
void to_csr(std::size_t ns, const std::vector<std::int32_t>& ps,
            const std::vector<std::int32_t>& pg, CandidateList& out) {
  out.offset.assign(ns + 1, 0);
  for (auto k : ps) ++out.offset[static_cast<std::size_t>(k) + 1];
  for (std::size_t k = 0; k < ns; ++k) out.offset[k + 1] += out.offset[k];
  out.segment.resize(ps.size());
  std::vector<std::int32_t> fill(out.offset.begin(), out.offset.end() - 1);
  for (std::size_t j = 0; j < ps.size(); ++j)
    out.segment[static_cast<std::size_t>(fill[static_cast<std::size_t>(ps[j])]++)] = pg[j];
}

}  // namespace

void bucket_search(const SearchInput& in, CandidateList& out, BucketWork& w) {
  const std::size_t ns = in.slave_count;
  w.pair_slave.clear();
  w.pair_seg.clear();
  if (ns == 0 || in.segment_count == 0) {
    to_csr(ns, w.pair_slave, w.pair_seg, out);
    return;
  }
  // Grid over the slave nodes' box; cell = the largest inflated segment box edge.
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::numeric_limits<double>::infinity();
    hi[d] = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t k = 0; k < ns; ++k) {
    const double* p = in.x + 3 * static_cast<std::size_t>(in.slaves[k]);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  double cell = 0.0;
  for (std::size_t i = 0; i < in.segment_count; ++i) {
    const Box b = segment_box(in, i);
    for (int d = 0; d < 3; ++d) cell = std::max(cell, b.hi[d] - b.lo[d]);
  }
  if (!(cell > 0.0)) cell = 1.0;
  const double max_cells = 2.0 * static_cast<double>(ns + in.segment_count) + 64.0;
  std::size_t dim[3];
  for (;;) {
    double total = 1.0;
    for (int d = 0; d < 3; ++d) total *= std::floor((hi[d] - lo[d]) / cell) + 1.0;
    if (total <= max_cells) break;
    cell *= 1.25;  // a sparse cloud of slaves: coarser cells keep the grid O(ns + nseg)
  }
  for (int d = 0; d < 3; ++d)
    dim[d] = static_cast<std::size_t>(std::floor((hi[d] - lo[d]) / cell)) + 1;
  const double inv = 1.0 / cell;
  const std::size_t ncell = dim[0] * dim[1] * dim[2];
  auto cell_of = [&](int d, double c) {
    const double f = std::floor((c - lo[d]) * inv);
    return static_cast<std::size_t>(std::min(std::max(f, 0.0), static_cast<double>(dim[d] - 1)));
  };
  // Bin the slave nodes (counting sort into CSR cells).
  w.count.assign(ns, 0);
  w.cell_start.assign(ncell + 1, 0);
  for (std::size_t k = 0; k < ns; ++k) {
    const double* p = in.x + 3 * static_cast<std::size_t>(in.slaves[k]);
    const std::size_t c =
        cell_of(0, p[0]) + dim[0] * (cell_of(1, p[1]) + dim[1] * cell_of(2, p[2]));
    w.count[k] = static_cast<std::int32_t>(c);
    ++w.cell_start[c + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) w.cell_start[c + 1] += w.cell_start[c];
  w.cell_nodes.resize(ns);
  {
    std::vector<std::int32_t> fill(w.cell_start.begin(), w.cell_start.end() - 1);
    for (std::size_t k = 0; k < ns; ++k)
      w.cell_nodes[static_cast<std::size_t>(fill[static_cast<std::size_t>(w.count[k])]++)] =
          static_cast<std::int32_t>(k);
  }
  // Each segment visits the cells its inflated box overlaps.
  for (std::size_t i = 0; i < in.segment_count; ++i) {
    const Box b = segment_box(in, i);
    bool outside = false;
    for (int d = 0; d < 3; ++d) outside = outside || b.hi[d] < lo[d] || b.lo[d] > hi[d];
    if (outside) continue;
    const std::size_t i0 = cell_of(0, b.lo[0]), i1 = cell_of(0, b.hi[0]);
    const std::size_t j0 = cell_of(1, b.lo[1]), j1 = cell_of(1, b.hi[1]);
    const std::size_t k0 = cell_of(2, b.lo[2]), k1 = cell_of(2, b.hi[2]);
    for (std::size_t kk = k0; kk <= k1; ++kk)
      for (std::size_t jj = j0; jj <= j1; ++jj)
        for (std::size_t ii = i0; ii <= i1; ++ii) {
          const std::size_t c = ii + dim[0] * (jj + dim[1] * kk);
          for (auto q = w.cell_start[c]; q < w.cell_start[c + 1]; ++q) {
            const std::int32_t k = w.cell_nodes[static_cast<std::size_t>(q)];
            if (inside(b, in.x + 3 * static_cast<std::size_t>(
                                         in.slaves[static_cast<std::size_t>(k)]))) {
              w.pair_slave.push_back(k);
              w.pair_seg.push_back(static_cast<std::int32_t>(i));
            }
          }
        }
  }
  to_csr(ns, w.pair_slave, w.pair_seg, out);
}

void brute_force_search(const SearchInput& in, CandidateList& out) {
  std::vector<std::int32_t> ps, pg;
  for (std::size_t i = 0; i < in.segment_count; ++i) {
    const Box b = segment_box(in, i);
    for (std::size_t k = 0; k < in.slave_count; ++k)
      if (inside(b, in.x + 3 * static_cast<std::size_t>(in.slaves[k]))) {
        ps.push_back(static_cast<std::int32_t>(k));
        pg.push_back(static_cast<std::int32_t>(i));
      }
  }
  to_csr(in.slave_count, ps, pg, out);
}

}  // namespace crashlink::contact
