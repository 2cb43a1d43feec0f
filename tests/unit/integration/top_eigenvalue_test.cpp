// TopEigenvalue (the global stable step's Lanczos process) against spectra known in closed form.
#include "solver/integration/top_eigenvalue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using crashlink::integration::TopEigenvalue;

namespace {

/// The 1-D Laplacian of a fixed-fixed chain of m unit masses and unit springs: the tridiagonal
/// (2, -1), eigenvalues 4 sin^2(k pi / (2 (m + 1))), k = 1..m; a dense spectrum near the top
/// (the hard case for an extreme-eigenvalue estimate).
void chain(const double* z, double* out, std::size_t m) {
  for (std::size_t i = 0; i < m; ++i)
    out[i] = 2.0 * z[i] - (i > 0 ? z[i - 1] : 0.0) - (i + 1 < m ? z[i + 1] : 0.0);
}

double chain_top(std::size_t m) {
  const double s =
      std::sin(static_cast<double>(m) * std::numbers::pi / (2.0 * (static_cast<double>(m) + 1.0)));
  return 4.0 * s * s;
}

}  // namespace

// A diagonal operator: the Krylov space of a start with every component reaches the top at once
// when there are fewer distinct eigenvalues than steps, and theta is then exact.
TEST(TopEigenvalue, FewDistinctEigenvaluesAreFoundExactly) {
  TopEigenvalue t;
  const std::size_t m = 300;
  t.reset(m, 16);
  const auto e = t.run(16, [&](const double* z, double* out) {
    for (std::size_t i = 0; i < m; ++i) out[i] = static_cast<double>(1 + i % 5) * z[i];
  });
  EXPECT_LE(e.steps, 6);  // invariant after 5 (one per distinct eigenvalue)
  EXPECT_NEAR(e.theta, 5.0, 1e-10);
  EXPECT_LT(e.residual, 1e-8);
}

// theta never exceeds lambda_max; theta + residual never falls below it; warm starts converge.
TEST(TopEigenvalue, ChainBracketsTheTopAndWarmStartsConverge) {
  const std::size_t m = 2000;
  const double top = chain_top(m);
  TopEigenvalue t;
  t.reset(m, 32);
  const auto apply = [&](const double* z, double* out) { chain(z, out, m); };
  auto e = t.run(32, apply);
  EXPECT_LE(e.theta, top * (1.0 + 1e-12));
  EXPECT_GE(e.theta + e.residual, top * (1.0 - 1e-12));
  const double first_gap = top - e.theta;
  for (int r = 0; r < 20; ++r) e = t.run(8, apply);
  EXPECT_LE(e.theta, top * (1.0 + 1e-12));
  EXPECT_GE(e.theta + e.residual, top * (1.0 - 1e-12));
  EXPECT_LT(top - e.theta, 0.5 * first_gap);  // the warm restarts kept improving it
  EXPECT_LT((top - e.theta) / top, 1e-3);
}

TEST(TopEigenvalue, TheSameInputsGiveTheSameBits) {
  const std::size_t m = 500;
  const auto apply = [&](const double* z, double* out) { chain(z, out, m); };
  TopEigenvalue a, b;
  a.reset(m, 12);
  b.reset(m, 12);
  const auto ea = a.run(12, apply), eb = b.run(12, apply);
  EXPECT_EQ(ea.theta, eb.theta);
  EXPECT_EQ(ea.residual, eb.residual);
  EXPECT_EQ(a.vector(), b.vector());
}
