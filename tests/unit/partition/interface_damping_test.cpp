// Interface damping of the layer scheme (model::InterfaceDamping, docs/decomposition.md layer step
// 6): the decomposition raises the damping ratio of the elements within n element layers of J on
// both sides (the moved layer is the fine side's first) and of no other element; the domains'
// stable steps include the damping (hex8.h: xi adds to the bulk viscosity's in the step).
#include <gtest/gtest.h>

#include <map>

#include "core/errors.h"
#include "solver/partition/decomposition.h"
#include "tests/unit/partition/partition_models.h"

namespace crashlink::partition {
namespace {

/// element id -> damping ratio over every domain of d.
std::map<std::int64_t, double> ratios(const Decomposition& d) {
  std::map<std::int64_t, double> r;
  for (const auto& dm : d.domains)
    for (const auto& p : dm.model.parts)
      for (std::size_t e = 0; e < p.element_count(); ++e)
        r[p.element_id[e]] = p.damping_ratio_of(e);
  return r;
}

TEST(InterfaceDamping, BarDampsNLayersEachSideOfJIncludingTheMovedLayer) {
  model::Model g = testing::bar_two_sizes();
  const Decomposition plain = decompose(g, Scheme::Layer);
  g.parts[1].damping_ratio = 0.1;  // an own ratio above the interface one is kept
  g.coupling.interface_damping = {0.06, 3};
  const Decomposition d = decompose(g, Scheme::Layer);
  // Coarse 1..10 (x 0..1), fine 11..20; element 10 moved, J at x = 0.9: layers 9, 8, 7 in C and
  // 10 (moved), 11, 12 in F.
  for (const auto& [id, xi] : ratios(d)) {
    SCOPED_TRACE(id);
    if (id >= 11)
      EXPECT_EQ(xi, 0.1);
    else if (id >= 7)
      EXPECT_EQ(xi, 0.06);
    else
      EXPECT_EQ(xi, 0.0);
  }
  // The coarse part: per-element ratios in both domains; the fine part keeps its own ratio only.
  for (const auto& dm : d.domains)
    for (std::size_t p = 0; p < dm.model.parts.size(); ++p)
      EXPECT_EQ(dm.model.parts[p].element_damping_ratio.empty(), dm.part_global[p] == 1)
          << dm.name << " " << dm.model.parts[p].name;
  // Damping shortens the stable step of the damped domains (the coarse one has no own damping).
  ASSERT_EQ(d.domain_dt_s.size(), plain.domain_dt_s.size());
  for (std::size_t k = 0; k < d.domain_dt_s.size(); ++k)
    EXPECT_LT(d.domain_dt_s[k], plain.domain_dt_s[k]) << d.domains[k].name;
  // Same cut otherwise.
  EXPECT_EQ(d.interfaces[0].moved_elements, plain.interfaces[0].moved_elements);
  EXPECT_EQ(d.interfaces[0].j_nodes_global, plain.interfaces[0].j_nodes_global);
}

TEST(InterfaceDamping, OneLayerAndOffAndPaper) {
  model::Model g = testing::bar_two_sizes();
  g.coupling.interface_damping = {0.05, 1};
  for (const auto& [id, xi] : ratios(decompose(g, Scheme::Layer)))
    EXPECT_EQ(xi, id == 9 || id == 10 ? 0.05 : 0.0) << id;
  g.coupling.interface_damping = {0.0, 3};  // off: no per-element ratios at all
  for (const auto& dm : decompose(g, Scheme::Layer).domains)
    for (const auto& p : dm.model.parts) EXPECT_FALSE(p.damped()) << dm.name;
  g.coupling.interface_damping = {0.06, 3};  // the paper scheme ignores it
  for (const auto& dm : decompose(g, Scheme::Paper).domains)
    for (const auto& p : dm.model.parts) EXPECT_FALSE(p.damped()) << dm.name;
}

TEST(InterfaceDamping, OutOfRangeIsAModelError) {
  model::Model g = testing::bar_two_sizes();
  g.coupling.interface_damping = {0.6, 3};
  EXPECT_THROW(model::validate(g), ModelError);
  g.coupling.interface_damping = {0.06, 0};
  EXPECT_THROW(model::validate(g), ModelError);
}

}  // namespace
}  // namespace crashlink::partition
