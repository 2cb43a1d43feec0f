// The sparse node sets of the nodal passes (integration/node_set.h): inserts once, walks in index
// order, clears only what it holds, and sparse_dot sums what the dense sum over every dof sums
// when the array is zero elsewhere.
#include "solver/integration/node_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using crashlink::integration::NodeSet;
using crashlink::integration::sparse_dot;

TEST(NodeSet, InsertsEachNodeOnceAndWalksThemInIndexOrder) {
  NodeSet s;
  s.reset(10);
  EXPECT_TRUE(s.empty());
  for (std::size_t i : {7u, 2u, 7u, 9u, 0u, 2u}) s.insert(i);
  s.sort();
  EXPECT_EQ(s.nodes(), (std::vector<std::int32_t>{0, 2, 7, 9}));
  s.clear();
  EXPECT_TRUE(s.empty());
  // cleared marks: the same nodes go in again
  s.insert(7);
  s.insert(7);
  EXPECT_EQ(s.nodes(), (std::vector<std::int32_t>{7}));
}

TEST(SparseDot, EqualsTheDenseSumWhenTheArrayIsZeroElsewhere) {
  // 1 000 nodes, forces on a scattered few; d everywhere (a displacement increment)
  const std::size_t n = 1000;
  std::vector<double> f(3 * n, 0.0), d(3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k)
    d[k] = 1e-4 * static_cast<double>((k * 7919) % 1013) - 0.05;
  NodeSet s;
  s.reset(n);
  for (std::size_t i : {997u, 3u, 500u, 255u, 256u, 4u}) {
    s.insert(i);
    for (std::size_t a = 0; a < 3; ++a) f[3 * i + a] = 1.0 + static_cast<double>(i + a);
  }
  s.sort();
  double dense = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < 3 * n; ++k) {
    dense += f[k] * d[k];
    scale += std::abs(f[k] * d[k]);
  }
  // the same terms in the same order; only contraction into FMAs may differ (one rounding per
  // term at most)
  EXPECT_NEAR(sparse_dot(s.nodes(), f.data(), d.data()), dense, 18 * 1.2e-16 * scale);
  // a node of the set left out changes it by its terms (here at least 1e-4 x 4)
  NodeSet fewer;
  fewer.reset(n);
  for (std::size_t i : {3u, 4u, 255u, 256u, 500u}) fewer.insert(i);
  EXPECT_GT(std::abs(sparse_dot(fewer.nodes(), f.data(), d.data()) - dense), 1e-4);
  // d computed where read (Solver::du_at): the same sum, and what it computes is what it sums
  const double dt = 0.5;
  std::vector<double> dd(3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k) dd[k] = dt * d[k];
  EXPECT_EQ(sparse_dot(s.nodes(), f.data(), [&](std::size_t k) { return dt * d[k]; }),
            sparse_dot(s.nodes(), f.data(), dd.data()));
  EXPECT_NE(sparse_dot(s.nodes(), f.data(), [&](std::size_t k) { return d[k]; }),
            sparse_dot(s.nodes(), f.data(), dd.data()));
}
