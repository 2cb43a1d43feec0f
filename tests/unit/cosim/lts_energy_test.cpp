// cosim::LtsEnergy: sampled only at the instants read and the two before each, it gives the bits
// of sampling every coarse instant; a gap in the instants starts the count again.
#include "solver/cosim/lts_energy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

using crashlink::cosim::LtsEnergy;

namespace {

/// Four nodes, two rotating (inertia > 0), node 3 a ghost, node 1's y held.
LtsEnergy make() {
  LtsEnergy e;
  e.reset({1, 1, 1, 0}, {0, 2, 0, 0}, {1.5, 2.0, 0.7, 3.0}, {0.0, 0.01, 0.02, 0.0}, 1e-6);
  return e;
}

/// A smooth motion with some noise, [12] per instant.
std::vector<double> motion(std::int64_t k, double scale) {
  std::vector<double> u(12);
  for (std::size_t i = 0; i < u.size(); ++i)
    u[i] = scale * (std::sin(0.3 * static_cast<double>(k) + static_cast<double>(i)) +
                    1e-3 * static_cast<double>((k * 7 + static_cast<std::int64_t>(i)) % 5));
  return u;
}

}  // namespace

TEST(LtsEnergy, SampledOnlyWhereReadGivesTheSameBits) {
  LtsEnergy all = make(), some = make();
  const std::set<std::int64_t> read{7, 12, 13, 30};
  const auto wanted = [&](std::int64_t k) { return read.count(k) != 0; };
  std::size_t checked = 0;
  for (std::int64_t k = 0; k <= 30; ++k) {
    // the rotations move every cycle (three per coarse instant here)
    for (int c = 0; c < 3; ++c) {
      const auto w = motion(3 * k + c, 0.2);
      all.add_rotation(w.data(), 1e-6 / 3.0);
      some.add_rotation(w.data(), 1e-6 / 3.0);
    }
    const auto u = motion(k, 1e-6);
    all.sample(u.data(), k, true);
    if (wanted(k) || wanted(k + 1) || wanted(k + 2)) some.sample(u.data(), k, wanted(k));
    if (!wanted(k)) continue;
    ASSERT_TRUE(all.ready());
    ASSERT_TRUE(some.ready()) << k;
    EXPECT_EQ(all.value_J(), some.value_J()) << k;
    EXPECT_NE(all.value_J(), 0.0);
    ++checked;
  }
  EXPECT_EQ(checked, read.size());
}

TEST(LtsEnergy, AGapStartsTheCountAgain) {
  LtsEnergy e = make();
  const auto u = motion(0, 1e-6);
  e.sample(u.data(), 0, true);
  e.sample(u.data(), 1, true);
  EXPECT_FALSE(e.ready());
  e.sample(u.data(), 3, true);  // instant 2 missing: not three consecutive
  EXPECT_FALSE(e.ready());
  e.sample(u.data(), 4, true);
  EXPECT_FALSE(e.ready());
  e.sample(u.data(), 5, false);  // not evaluated
  EXPECT_FALSE(e.ready());
  e.sample(u.data(), 6, true);
  EXPECT_TRUE(e.ready());
}
