// The `layer` decomposition (docs/design.md §2.7, docs/decomposition.md): the coarse side's first
// element layer moves into the fine domain, J = the layer's far nodes (ghosts in fine, owned by
// coarse with their natural summed mass), every contact inside one domain.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "core/errors.h"
#include "solver/partition/decomposition.h"
#include "tests/unit/partition/partition_models.h"

namespace crashlink::partition {
namespace {

using testing::check_invariants;
using testing::domain_index;
using testing::local_of;

std::vector<std::int32_t> nodes_at_x(const model::Model& m, double x0) {
  return testing::where(m, [x0](double x, double, double) { return std::abs(x - x0) < 1e-9; });
}

std::size_t ghosts(const DomainModel& d) {
  std::size_t n = 0;
  for (auto g : d.ghost) n += g;
  return n;
}

TEST(Layer, BarMovesTheCoarseElementAtTheInterfaceAndJIsThePlaneBehindIt) {
  for (bool fine_first : {false, true}) {
    const auto g = testing::bar_two_sizes(fine_first);
    const auto d = decompose(g, Scheme::Layer);
    check_invariants(g, d);
    const int c = domain_index(d, "coarse"), f = domain_index(d, "fine");
    ASSERT_EQ(d.interfaces.size(), 1u);
    const auto& itf = d.interfaces[0];
    // The fine/coarse choice follows the steps (0.05 m vs 0.1 m elements: ratio 2), not the order.
    EXPECT_EQ(itf.fine, f);
    EXPECT_EQ(itf.coarse, c);
    EXPECT_EQ(itf.kind, "link");
    // (the hex step is not exactly proportional to the element length: about 1.85)
    const double ratio =
        d.domain_dt_s[static_cast<std::size_t>(c)] / d.domain_dt_s[static_cast<std::size_t>(f)];
    EXPECT_GT(ratio, 1.5);
    EXPECT_LT(ratio, 2.5);
    // Coarse elements have ids 1..10 (x in [0, 1]); the one touching x = 1 (id 10) moves.
    EXPECT_EQ(itf.moved_elements, std::vector<std::int64_t>{10});
    // J = the node plane x = 0.9, one element into the coarse side, mass rho V / 8 from each of
    // the two coarse elements around it.
    EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 0.9));
    for (double mj : itf.j_mass_kg) EXPECT_NEAR(mj, 2.0 * 7850.0 * 0.1 * 0.2 * 0.2 / 8.0, 1e-12);
    const auto& fd = d.domains[static_cast<std::size_t>(f)];
    const auto& cd = d.domains[static_cast<std::size_t>(c)];
    // fine: planes x = 0.9 .. 1.5 (12 x 4 nodes), the 4 of x = 0.9 ghosts; parts coarse (1) + fine.
    EXPECT_EQ(fd.global_node.size(), 48u);
    EXPECT_EQ(ghosts(fd), 4u);
    ASSERT_EQ(fd.model.parts.size(), 2u);
    EXPECT_EQ(fd.model.parts[0].name, "coarse");
    EXPECT_EQ(fd.model.parts[0].element_id, std::vector<std::int64_t>{10});
    EXPECT_EQ(fd.model.parts[1].element_count(), 10u);
    // coarse: planes x = 0 .. 0.9 (40 nodes), J owned with the summed mass, 9 elements.
    EXPECT_EQ(cd.global_node.size(), 40u);
    EXPECT_EQ(ghosts(cd), 0u);
    EXPECT_EQ(cd.model.element_count(), 9u);
    for (auto j : itf.j_nodes_global) {
      const int l = local_of(cd, j);
      ASSERT_GE(l, 0);
      EXPECT_GT(cd.interface_mass_kg[static_cast<std::size_t>(l)], 0.0);
    }
    // Conditions: fixed end in coarse, the load on the tip in fine, probes to the owners,
    // initial velocity on owned nodes only.
    EXPECT_EQ(cd.model.fixed[0], 7);
    ASSERT_EQ(fd.model.loads.size(), 1u);
    EXPECT_EQ(fd.model.loads[0].nodes.size(), 4u);
    EXPECT_TRUE(cd.model.loads.empty());
    ASSERT_EQ(fd.model.probes.size(), 1u);
    EXPECT_EQ(fd.model.probes[0].name, "tip");
    ASSERT_EQ(cd.model.probes.size(), 1u);
    EXPECT_EQ(cd.model.probes[0].name, "j");
    ASSERT_EQ(fd.model.initial_velocities.size(), 1u);
    // 44 owned nodes plus the 4 ghosts J: the forces at t = 0 need the ghosts' velocity too
    // (multirate_bar_test RatioOneReproducesMono fails at 1e-5 without it).
    EXPECT_EQ(fd.model.initial_velocities[0].nodes.size(), 48u);
    EXPECT_EQ(cd.model.initial_velocities[0].nodes.size(), 40u);
  }
}

TEST(Layer, ShellPlateCutAlongALine) {
  const auto g = testing::plate_cut();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, domain_index(d, "right"));
  EXPECT_EQ(itf.coarse, domain_index(d, "left"));
  EXPECT_EQ(itf.moved_elements.size(), 8u);  // the left column at x in [0.375, 0.5]
  EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 0.375));
  EXPECT_EQ(itf.j_nodes_global.size(), 9u);
}

TEST(Layer, HexBlock) {
  const auto g = testing::hex_block();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, domain_index(d, "fine"));
  EXPECT_EQ(itf.moved_elements.size(), 4u);  // the 2 x 2 coarse elements at x in [0.5, 1]
  EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 0.5));
  EXPECT_EQ(d.domains[static_cast<std::size_t>(domain_index(d, "coarse"))].model.element_count(),
            4u);
}

TEST(Layer, ThreeDomainsInAChainWithThreeSteps) {
  for (const auto& order :
       std::vector<std::vector<model::Domain>>{{{"coarse", {0}}, {"mid", {1}}, {"fine", {2}}},
                                               {{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}}}) {
    const auto g = testing::chain3(order);
    const auto d = decompose(g, Scheme::Layer);
    check_invariants(g, d);
    const int c = domain_index(d, "coarse"), m = domain_index(d, "mid"),
              f = domain_index(d, "fine");
    const auto dt = [&](int k) { return d.domain_dt_s[static_cast<std::size_t>(k)]; };
    EXPECT_LT(dt(f), dt(m));
    EXPECT_LT(dt(m), dt(c));
    ASSERT_EQ(d.interfaces.size(), 2u);
    for (const auto& itf : d.interfaces) {
      if (itf.coarse == c) {
        EXPECT_EQ(itf.fine, m);
        EXPECT_EQ(itf.moved_elements, std::vector<std::int64_t>{5});  // coarse x in [0.8, 1]
        EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 0.8));
      } else {
        EXPECT_EQ(itf.coarse, m);
        EXPECT_EQ(itf.fine, f);
        EXPECT_EQ(itf.moved_elements, std::vector<std::int64_t>{10});  // mid x in [1.4, 1.5]
        EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 1.4));
      }
    }
    // mid: the moved coarse element + mid elements 6..9; ghosts at x = 0.8, owns x = 1.0 .. 1.4
    // (1.4 being the J of the fine interface).
    const auto& md = d.domains[static_cast<std::size_t>(m)];
    EXPECT_EQ(md.model.element_count(), 5u);
    EXPECT_EQ(md.global_node.size(), 24u);
    EXPECT_EQ(ghosts(md), 4u);
  }
}

TEST(Layer, NodeSharedByThreeDomains) {
  const auto g = testing::quadrants3();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  const int a = domain_index(d, "a"), b = domain_index(d, "b"), c = domain_index(d, "c");
  EXPECT_LT(d.domain_dt_s[static_cast<std::size_t>(a)], d.domain_dt_s[static_cast<std::size_t>(b)]);
  EXPECT_LT(d.domain_dt_s[static_cast<std::size_t>(b)], d.domain_dt_s[static_cast<std::size_t>(c)]);
  // The centre: every element around it goes to the finest domain, which owns it alone.
  const auto centre = testing::where(
      g, [](double x, double y, double) { return std::abs(x) < 1e-9 && std::abs(y) < 1e-9; });
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_EQ(local_of(d.domains[static_cast<std::size_t>(b)], centre[0]), -1);
  EXPECT_EQ(local_of(d.domains[static_cast<std::size_t>(c)], centre[0]), -1);
  ASSERT_GE(local_of(d.domains[static_cast<std::size_t>(a)], centre[0]), 0);
  // Interfaces a-b, a-c, b-c; domain a has two of them, each with coarse = the larger step.
  std::set<std::pair<int, int>> pairs;
  for (const auto& itf : d.interfaces) pairs.insert({itf.fine, itf.coarse});
  EXPECT_EQ(pairs, (std::set<std::pair<int, int>>{{a, b}, {a, c}, {b, c}}));
  // Moved: b's column at x = 0 (4) into a; c's row at y = 0 into a (q4: 4, q3's corner: 1) and
  // the rest of q3's row (3) into b.
  std::size_t into_a = 0, into_b = 0;
  for (const auto& itf : d.interfaces)
    (itf.fine == a ? into_a : into_b) += itf.moved_elements.size();
  EXPECT_EQ(into_a, 9u);
  EXPECT_EQ(into_b, 3u);
}

TEST(Layer, RigidSphereMovesWholeIntoThePlateDomainWithTheContact) {
  const auto g = testing::sphere_over_plate();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  const int p = domain_index(d, "plate"), h = domain_index(d, "head");
  EXPECT_TRUE(std::isinf(d.domain_dt_s[static_cast<std::size_t>(h)]));  // rigid only: no step
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, p);
  EXPECT_EQ(itf.coarse, h);
  EXPECT_EQ(itf.kind, "contact:head_on_plate");
  EXPECT_EQ(itf.moved_elements.size(), g.parts[1].element_count());  // the whole rigid body
  EXPECT_TRUE(itf.j_nodes_global.empty());
  const auto& pd = d.domains[static_cast<std::size_t>(p)];
  EXPECT_TRUE(d.domains[static_cast<std::size_t>(h)].empty());
  ASSERT_EQ(pd.model.contacts.size(), 1u);
  ASSERT_EQ(pd.model.rigid_bodies.size(), 1u);
  ASSERT_EQ(pd.model.probes.size(), 1u);
  EXPECT_EQ(pd.model.probes[0].kind, model::Probe::Kind::RigidBody);
  const auto& ct = pd.model.contacts[0];
  EXPECT_EQ(ct.slave_nodes.size(), 81u);
  ASSERT_EQ(ct.master_parts.size(), 1u);
  EXPECT_EQ(pd.model.parts[static_cast<std::size_t>(ct.master_parts[0])].name, "sphere");
  for (std::size_t j = 0; j < ct.slave_nodes.size(); ++j)
    EXPECT_EQ(pd.global_node[static_cast<std::size_t>(ct.slave_nodes[j])],
              g.contacts[0].slave_nodes[j]);
}

TEST(Layer, CoarseMasterSurfaceMovesIntoTheFineDomain) {
  const auto g = testing::block_on_floor();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  const int fl = domain_index(d, "floor"), bl = domain_index(d, "block");
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, bl);
  EXPECT_EQ(itf.coarse, fl);
  EXPECT_EQ(itf.kind, "contact:block_on_plate");
  EXPECT_EQ(itf.moved_elements.size(), 16u);          // the whole master part "plate"
  EXPECT_EQ(itf.j_nodes_global, nodes_at_x(g, 0.5));  // the plate/frame line
  const auto& bd = d.domains[static_cast<std::size_t>(bl)];
  ASSERT_EQ(bd.model.contacts.size(), 1u);
  EXPECT_EQ(bd.model.parts[static_cast<std::size_t>(bd.model.contacts[0].master_parts[0])].name,
            "plate");
  EXPECT_TRUE(d.domains[static_cast<std::size_t>(fl)].model.contacts.empty());
  EXPECT_EQ(d.domains[static_cast<std::size_t>(fl)].model.element_count(), 16u);  // the frame
}

TEST(Layer, CoarseSlaveSideMovesTheElementsHoldingSlaveNodes) {
  const auto g = testing::ball_on_ground();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  const int gr = domain_index(d, "ground"), ba = domain_index(d, "ball");
  ASSERT_EQ(d.interfaces.size(), 1u);
  const auto& itf = d.interfaces[0];
  EXPECT_EQ(itf.fine, ba);
  EXPECT_EQ(itf.coarse, gr);
  EXPECT_EQ(g.contacts[0].slave_nodes.size(), 9u);
  EXPECT_EQ(itf.moved_elements.size(), 16u);  // the 4 x 4 elements in [-0.25, 0.25]^2
  EXPECT_EQ(itf.j_nodes_global.size(), 16u);  // the perimeter of that square
  for (auto j : itf.j_nodes_global) {
    const double x = g.nodes.x0[3 * static_cast<std::size_t>(j)];
    const double y = g.nodes.x0[3 * static_cast<std::size_t>(j) + 1];
    EXPECT_NEAR(std::max(std::abs(x), std::abs(y)), 0.25, 1e-9);
  }
  EXPECT_EQ(d.domains[static_cast<std::size_t>(ba)].model.contacts.size(), 1u);
}

TEST(Layer, NoDomainsIsOneDomainWithEverything) {
  auto g = testing::bar_two_sizes();
  g.domains.clear();
  const auto d = decompose(g, Scheme::Layer);
  check_invariants(g, d);
  ASSERT_EQ(d.domains.size(), 1u);
  EXPECT_EQ(d.domains[0].name, "model");
  EXPECT_TRUE(d.interfaces.empty());
  EXPECT_EQ(d.domains[0].model.element_count(), 20u);
}

TEST(Layer, BadDomainsAreModelErrorsWithTheFix) {
  auto expect_error = [](const model::Model& g, const std::string& fragment) {
    try {
      (void)decompose(g, Scheme::Layer);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  auto g = testing::bar_two_sizes();
  g.domains = {{"a", {0}}};
  expect_error(g, "parts 'fine' are in no domain");
  g.domains = {{"a", {0, 1}}, {"b", {1}}};
  expect_error(g, "part 'fine' is in domains 'a' and 'b'");
  g.domains = {{"a", {0, 1}}, {"b", {}}};
  expect_error(g, "domain 'b' holds no part");
  // A rigid body split over two domains (checked before anything else).
  auto h = testing::sphere_over_plate();
  h.rigid_bodies[0].parts = {1, 0};
  expect_error(h, "rigid body 'head' has parts in domains 'head' and 'plate'");
  // A contact whose slave nodes lie in two domains besides the master's.
  auto q = testing::quadrants3();
  q.domains = {{"a", {0}}, {"b", {1}}, {"c", {2}}, {"d", {3}}};
  model::Contact ct;
  ct.name = "wide";
  ct.master_parts = {0};
  ct.slave_nodes =
      testing::where(q, [](double x, double y, double) { return x < -0.3 || y < -0.3; });
  q.contacts.push_back(ct);
  expect_error(q, "split it into one contact per slave domain");
}

// The `lts` overlap (decompose(..., overlap_layers)): the link claim repeated on the assignment so
// far, beyond the links' moved layer and the contact surfaces' alike (docs/decomposition.md).
TEST(Layer, OverlapLayersMoveMoreCoarseLayersPastLinksAndContactSurfaces) {
  for (bool fine_first : {false, true}) {  // either domain order
    const auto g = testing::bar_two_sizes(fine_first);
    const auto d = decompose(g, Scheme::Layer, 2);
    check_invariants(g, d);
    ASSERT_EQ(d.interfaces.size(), 1u);
    EXPECT_EQ(d.overlap_layers, 2);
    EXPECT_EQ(d.interfaces[0].fine, domain_index(d, "fine"));
    // coarse elements 8, 9, 10 (x in [0.7, 1]) move; J is the plane x = 0.7
    EXPECT_EQ(d.interfaces[0].moved_elements, (std::vector<std::int64_t>{8, 9, 10}));
    EXPECT_EQ(d.interfaces[0].j_nodes_global, nodes_at_x(g, 0.7));
  }
  {
    // The plate (the coarse side's contact surface) moves into the block's domain; with one
    // overlap layer the frame's first column (x in [0.5, 0.625]) follows, and J is x = 0.625.
    const auto g = testing::block_on_floor();
    const auto plain = decompose(g, Scheme::Layer);
    const auto d = decompose(g, Scheme::Layer, 1);
    check_invariants(g, d);
    ASSERT_EQ(d.interfaces.size(), 1u);
    ASSERT_EQ(plain.interfaces.size(), 1u);
    EXPECT_EQ(d.interfaces[0].moved_elements.size(), plain.interfaces[0].moved_elements.size() + 4);
    std::vector<std::int32_t> j625;
    for (const auto j : d.interfaces[0].j_nodes_global)
      if (std::abs(g.nodes.x0[3 * static_cast<std::size_t>(j)] - 0.625) < 1e-9) j625.push_back(j);
    EXPECT_EQ(j625.size(), d.interfaces[0].j_nodes_global.size());
    EXPECT_EQ(j625.size(), 5u);
    EXPECT_EQ(d.interfaces[0].kind, plain.interfaces[0].kind);  // overlap moves are no link
  }
  {
    auto g = testing::bar_two_sizes();  // interface damping is a `layer` option
    g.coupling.interface_damping.ratio = 0.06;
    EXPECT_NO_THROW(decompose(g, Scheme::Layer));
    EXPECT_THROW(decompose(g, Scheme::Layer, 1), ModelError);
  }
  EXPECT_THROW(decompose(testing::bar_two_sizes(), Scheme::Paper, 1), ModelError);
}

}  // namespace
}  // namespace crashlink::partition
