// coordinator::layer_cut / check_register / plan_steps / setup_message (layer_cut.h): what the
// coordinator checks in a daemon's Register against its own cut of the scenario, and the Setup.
#include "coordinator/layer_cut.h"

#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"
#include "coupling/interface_match.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;

namespace {

struct Fixture {
  model::Model m = crashlink::testing::bar_two_sizes();
  partition::Decomposition dec = partition::decompose(m, partition::Scheme::Layer);
  coordinator::LayerCut cut = coordinator::layer_cut(m, dec);

  /// What daemon k registers when it cut the same model.
  wire::Register honest(int k, std::int64_t step) const {
    wire::Register r;
    r.set_stable_step_ticks(step);
    for (const auto& c : cut.interfaces) {
      if (c.fine != k && c.coarse != k) continue;
      auto* li = r.add_layer_interfaces();
      li->set_index(c.index);
      li->set_fine_side(c.fine == k);
      for (std::size_t j = 0; j < c.j_node_ids.size(); ++j) {
        li->add_j_node_ids(c.j_node_ids[j]);
        li->add_masses_kg(c.fine == k ? 0.0 : 1.0);
        const auto g = static_cast<std::size_t>(dec.interfaces[c.index].j_nodes_global[j]);
        for (std::size_t d = 0; d < 3; ++d) li->add_positions_m(m.nodes.x0[3 * g + d]);
      }
    }
    return r;
  }
};

int index_of(const coordinator::LayerCut& cut, const std::string& name) {
  for (std::size_t k = 0; k < cut.names.size(); ++k)
    if (cut.names[k] == name) return static_cast<int>(k);
  return -1;
}

}  // namespace

TEST(LayerCut, NamesTheInterfaceAfterItsSides) {
  Fixture f;
  ASSERT_EQ(f.cut.names.size(), 2u);
  ASSERT_EQ(f.cut.interfaces.size(), 1u);
  EXPECT_EQ(f.cut.interfaces[0].name, "fine-coarse");
  EXPECT_EQ(f.cut.names[static_cast<std::size_t>(f.cut.interfaces[0].fine)], "fine");
  EXPECT_FALSE(f.cut.interfaces[0].j_node_ids.empty());
}

TEST(LayerCut, AcceptsHonestRegistersAndPlansNestedSteps) {
  Fixture f;
  const int fine = index_of(f.cut, "fine"), coarse = index_of(f.cut, "coarse");
  std::vector<wire::Register> regs(2);
  regs[static_cast<std::size_t>(fine)] = f.honest(fine, 1000);
  regs[static_cast<std::size_t>(coarse)] = f.honest(coarse, 3000);
  for (int k : {fine, coarse})
    EXPECT_NO_THROW(coordinator::check_register(f.cut, k, regs[static_cast<std::size_t>(k)]));
  EXPECT_NO_THROW(coordinator::match_sides(f.cut, regs));
  const auto multi = coordinator::plan_steps(f.cut, regs, false);
  EXPECT_EQ(multi.step[static_cast<std::size_t>(coarse)], 3000);
  EXPECT_EQ(multi.step[static_cast<std::size_t>(fine)], 1000);
  const auto split = coordinator::plan_steps(f.cut, regs, true);
  EXPECT_EQ(split.step[static_cast<std::size_t>(coarse)], 1000);
  const auto e = coordinator::setup_message(f.cut, multi, fine, false, {}, 1'000'000);
  ASSERT_TRUE(e.has_setup());
  EXPECT_EQ(e.setup().step_ticks(), 1000);
  ASSERT_EQ(e.setup().layer_interfaces_size(), 1);
  EXPECT_TRUE(e.setup().layer_interfaces(0).fine_side());
  EXPECT_EQ(e.setup().layer_interfaces(0).partner(), "coarse");
  EXPECT_EQ(e.setup().layer_interfaces(0).partner_step_ticks(), 3000);
  EXPECT_EQ(e.setup().mode(), wire::MODE_MULTI);
}

TEST(LayerCut, RefusesAnotherJNodeNamingDomainAndIds) {
  Fixture f;
  const int fine = index_of(f.cut, "fine");
  auto r = f.honest(fine, 1000);
  const auto expected = r.layer_interfaces(0).j_node_ids(1);
  r.mutable_layer_interfaces(0)->set_j_node_ids(1, 99999);
  try {
    coordinator::check_register(f.cut, fine, r);
    ADD_FAILURE() << "a Register with another J node was accepted";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'fine'"), std::string::npos) << what;
    EXPECT_NE(what.find("99999"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(expected)), std::string::npos) << what;
  }
}

TEST(LayerCut, RefusesWrongSideAndMissingInterface) {
  Fixture f;
  const int fine = index_of(f.cut, "fine");
  auto side = f.honest(fine, 1000);
  side.mutable_layer_interfaces(0)->set_fine_side(false);
  EXPECT_THROW(coordinator::check_register(f.cut, fine, side), ModelError);
  wire::Register none;
  EXPECT_THROW(coordinator::check_register(f.cut, fine, none), ModelError);
}

TEST(LayerCut, MatchSidesRefusesMovedCopies) {
  Fixture f;
  const int fine = index_of(f.cut, "fine"), coarse = index_of(f.cut, "coarse");
  std::vector<wire::Register> regs(2);
  regs[static_cast<std::size_t>(fine)] = f.honest(fine, 1000);
  regs[static_cast<std::size_t>(coarse)] = f.honest(coarse, 3000);
  regs[static_cast<std::size_t>(fine)].mutable_layer_interfaces(0)->set_positions_m(0, 0.5);
  EXPECT_THROW(coordinator::match_sides(f.cut, regs), coupling::InterfaceError);
}
