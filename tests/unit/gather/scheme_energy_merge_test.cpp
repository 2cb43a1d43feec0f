// The gather's sum of the lts energy shares (gather::merge_glstat, GlstatSample::scheme_energy_J
// and scheme_energy_time_s): each merged row adds every domain's share of the grid row's coarse
// instant, whatever the domains' order and row times. The case (from review): a fine domain
// (step 1 tick) listed first and a coarse one (step 3) with one row per history instant each
// (every 4 ticks), so the row counts tie and the fine domain is the grid. Its row of instant 4
// comes at t = 4, the coarse domain's at t = 6: matching by time would add the coarse share of
// instant 0 to the fine share of instant 3.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solver/gather/history_merge.h"

namespace {

using crashlink::io::GlstatSample;

GlstatSample row(double t, double key, double share) {
  GlstatSample g;
  g.time_s = t;
  g.kinetic_energy_J = 1.0;
  g.total_energy_J = 1.0;
  g.scheme_energy_time_s = key;
  g.scheme_energy_J = share;
  return g;
}

TEST(SchemeEnergyMerge, SharesOfTheSameCoarseInstantAreAddedWhateverTheGrid) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  // history instants 0, 4, 8, 12; coarse instants at or before them: 0, 3, 6, 12
  auto fine_share = [](double k) { return 10.0 + k; };
  auto coarse_share = [](double k) { return 100.0 + 2.0 * k; };
  const std::vector<GlstatSample> fine = {row(0, nan, nan), row(4, 3, fine_share(3)),
                                          row(8, 6, fine_share(6)), row(12, 12, fine_share(12))};
  const std::vector<GlstatSample> coarse = {row(0, nan, nan), row(6, 3, coarse_share(3)),
                                            row(9, 6, coarse_share(6)),
                                            row(12, 12, coarse_share(12))};
  const auto m = crashlink::gather::merge_glstat({fine, coarse});
  ASSERT_EQ(m.grid, 0u);  // the tie: the first domain, the fine one
  ASSERT_EQ(m.rows.size(), 4u);
  EXPECT_TRUE(std::isnan(m.rows[0].scheme_energy_J));
  const double keys[] = {3, 6, 12};
  for (std::size_t r = 1; r < 4; ++r) {
    const double k = keys[r - 1];
    EXPECT_EQ(m.rows[r].scheme_energy_time_s, k) << "row " << r;
    EXPECT_EQ(m.rows[r].scheme_energy_J, fine_share(k) + coarse_share(k)) << "row " << r;
  }
  // a domain without a row of the instant: NaN, not a sum of other instants
  auto gap = coarse;
  gap[2] = row(9, 3, coarse_share(3));  // instant 6 missing
  const auto g = crashlink::gather::merge_glstat({fine, gap});
  EXPECT_TRUE(std::isnan(g.rows[2].scheme_energy_J));
  EXPECT_EQ(g.rows[3].scheme_energy_J, fine_share(12) + coarse_share(12));
  // domains without the column (mono, layer): NaN everywhere
  std::vector<GlstatSample> plain = fine, plain2 = coarse;
  for (auto* d : {&plain, &plain2})
    for (auto& x : *d) x.scheme_energy_J = x.scheme_energy_time_s = nan;
  for (const auto& x : crashlink::gather::merge_glstat({plain, plain2}).rows)
    EXPECT_TRUE(std::isnan(x.scheme_energy_J));
}

}  // namespace
