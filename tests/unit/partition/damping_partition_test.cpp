// The decomposition carries the stiffness-proportional damping of every part into the domains'
// parts: Part::damping_ratio as is, Part::element_damping_ratio sliced with the elements placed
// in the domain (including the coarse layer that `layer` moves into the fine domain).
#include <gtest/gtest.h>

#include "solver/partition/decomposition.h"
#include "tests/unit/partition/partition_models.h"

namespace crashlink::partition {
namespace {

TEST(DampingPartition, RatiosFollowTheirElementsIntoTheDomains) {
  model::Model g = testing::bar_two_sizes();
  auto& coarse = g.parts[0];
  coarse.damping_ratio = 0.02;
  for (std::size_t e = 0; e < coarse.element_count(); ++e)
    coarse.element_damping_ratio.push_back(0.01 * static_cast<double>(e % 5));
  g.parts[1].damping_ratio = 0.05;
  for (Scheme scheme : {Scheme::Layer, Scheme::Paper}) {
    SCOPED_TRACE(scheme_name(scheme));
    const Decomposition d = decompose(g, scheme);
    std::size_t moved = 0;
    for (const auto& dm : d.domains)
      for (std::size_t p = 0; p < dm.model.parts.size(); ++p) {
        const auto& lp = dm.model.parts[p];
        const auto& gp = g.parts[static_cast<std::size_t>(dm.part_global[p])];
        EXPECT_EQ(lp.damping_ratio, gp.damping_ratio);
        ASSERT_EQ(lp.element_damping_ratio.size(),
                  gp.element_damping_ratio.empty() ? 0u : lp.element_count());
        for (std::size_t e = 0; e < lp.element_damping_ratio.size(); ++e) {
          const auto ge = static_cast<std::size_t>(dm.part_elements[p][e]);
          EXPECT_EQ(lp.element_id[e], gp.element_id[ge]);
          EXPECT_EQ(lp.element_damping_ratio[e], gp.element_damping_ratio[ge]);
        }
        if (dm.name == "fine" && dm.part_global[p] == 0) moved += lp.element_count();
      }
    // layer: the coarse element at the interface went to the fine domain with its ratio
    EXPECT_EQ(moved, scheme == Scheme::Layer ? 1u : 0u);
  }
}

}  // namespace
}  // namespace crashlink::partition
