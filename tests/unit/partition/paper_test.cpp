// The `paper` decomposition (docs/design.md §2.2, §2.5; Bourel 2005 §2.3 [3]-[8], §3.1): no element
// moves, link nodes are present in every domain using them with partial masses, and a contact
// across domains is computed in the master's domain on copies of the slave nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "solver/partition/decomposition.h"
#include "tests/unit/partition/partition_models.h"

namespace crashlink::partition {
namespace {

using testing::check_invariants;
using testing::domain_index;
using testing::local_of;

TEST(Paper, BarSharesTheInterfacePlaneWithPartialMasses) {
  const auto g = testing::bar_two_sizes();
  const auto d = decompose(g, Scheme::Paper);
  check_invariants(g, d);
  const int c = domain_index(d, "coarse"), f = domain_index(d, "fine");
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, f);
  EXPECT_EQ(itf.coarse, c);
  EXPECT_EQ(itf.reference, c);  // a permanent link: the larger step is the reference [11]
  EXPECT_EQ(itf.kind, "link");
  EXPECT_TRUE(itf.moved_elements.empty());
  const auto plane =
      testing::where(g, [](double x, double, double) { return std::abs(x - 1.0) < 1e-9; });
  EXPECT_EQ(itf.j_nodes_global, plane);
  // M = m^coarse + m^fine (§2.2): rho V / 8 of one coarse and one fine element.
  const double m_sum = 7850.0 * (0.1 + 0.05) * 0.2 * 0.2 / 8.0;
  for (double mj : itf.j_mass_kg) EXPECT_NEAR(mj, m_sum, 1e-12);
  for (int k : {c, f}) {
    const auto& dm = d.domains[static_cast<std::size_t>(k)];
    const auto lm = testing::lumped_mass(dm.model);
    EXPECT_EQ(dm.model.element_count(), 10u);
    EXPECT_EQ(dm.global_node.size(), 44u);
    for (auto j : plane) {
      const int l = local_of(dm, j);
      ASSERT_GE(l, 0);
      EXPECT_EQ(dm.ghost[static_cast<std::size_t>(l)], 0);
      EXPECT_NEAR(dm.interface_mass_kg[static_cast<std::size_t>(l)], m_sum, 1e-12);
      EXPECT_LT(lm[static_cast<std::size_t>(l)], m_sum);  // partial
    }
  }
}

TEST(Paper, ContactGetsCopiesOfTheSlaveNodesInTheMasterDomain) {
  const auto g = testing::sphere_over_plate();
  const auto d = decompose(g, Scheme::Paper);
  check_invariants(g, d);
  const int p = domain_index(d, "plate"), h = domain_index(d, "head");
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.kind, "contact:head_on_plate");
  EXPECT_EQ(itf.reference, p);  // the domain owning the originals
  EXPECT_EQ(itf.fine, p);
  EXPECT_EQ(itf.coarse, h);
  EXPECT_EQ(itf.j_nodes_global, g.contacts[0].slave_nodes);
  const auto& hd = d.domains[static_cast<std::size_t>(h)];
  const auto& pd = d.domains[static_cast<std::size_t>(p)];
  ASSERT_EQ(hd.model.contacts.size(), 1u);
  EXPECT_TRUE(pd.model.contacts.empty());
  std::size_t copies = 0;
  for (auto cp : hd.copy) copies += cp;
  EXPECT_EQ(copies, 81u);
  const auto& ct = hd.model.contacts[0];
  for (std::size_t j = 0; j < ct.slave_nodes.size(); ++j) {
    const auto l = static_cast<std::size_t>(ct.slave_nodes[j]);
    EXPECT_EQ(hd.copy[l], 1);
    EXPECT_EQ(hd.ghost[l], 0);
    EXPECT_EQ(hd.global_node[l], g.contacts[0].slave_nodes[j]);
    EXPECT_GT(hd.interface_mass_kg[l], 0.0);
  }
  EXPECT_EQ(hd.model.parts.size(), 1u);  // the sphere only: copies carry no element
  EXPECT_EQ(pd.model.parts.size(), 1u);
}

TEST(Paper, NodeSharedByThreeDomainsIsInEachWithThreeLinks) {
  const auto g = testing::quadrants3();
  const auto d = decompose(g, Scheme::Paper);
  check_invariants(g, d);
  const auto centre = testing::where(
      g, [](double x, double y, double) { return std::abs(x) < 1e-9 && std::abs(y) < 1e-9; });
  for (const auto& dm : d.domains) EXPECT_GE(local_of(dm, centre[0]), 0) << dm.name;
  std::size_t links_with_centre = 0;
  for (const auto& itf : d.interfaces)
    for (auto j : itf.j_nodes_global) links_with_centre += j == centre[0] ? 1 : 0;
  EXPECT_EQ(links_with_centre, 3u);
}

TEST(Paper, ChainOfThree) {
  const auto g = testing::chain3();
  const auto d = decompose(g, Scheme::Paper);
  check_invariants(g, d);
  ASSERT_EQ(d.interfaces.size(), 2u);
  for (const auto& itf : d.interfaces) EXPECT_EQ(itf.j_nodes_global.size(), 4u);
}

}  // namespace
}  // namespace crashlink::partition
