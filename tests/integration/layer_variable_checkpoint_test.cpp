// Checkpoints of `layer` runs with variable steps (layer_stepper.h advance(), save_state; docs/
// checkpoints.md "Variable steps"), in the in-process LayerNetwork, on the three-domain chain
// fine | mid | coarse, where the middle domain follows the coarse one and leads the fine one:
// - the whole chain pauses at one instant, the coarse leader's first instant at or after
//   `until` (mid and fine land on it, flagged by their owners' u_J), not at instants of their own;
// - a run saved there and restored into a fresh network ends with the uninterrupted run's bits,
//   and so does the paused run itself (a pause changes nothing).
// The same over processes, killed and restarted: CheckpointRestart.*/Variable.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/state_archive.h"
#include "solver/cosim/layer_network.h"
#include "tests/integration/network_helpers.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

model::Model pulsed_chain() {
  return pulsed_chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}}, 2e-3, 2e-4, -1e5);
}

cosim::LayerNetworkOptions variable() {
  cosim::LayerNetworkOptions o;
  o.run.variable_steps = true;
  o.step_safety = 0.9;
  return o;
}

cosim::Tick ticks(const cosim::LayerNetwork& net, double t_s) {
  return static_cast<cosim::Tick>(t_s * static_cast<double>(net.stepper(0).ticks_per_second()));
}

std::size_t index_of(const cosim::LayerNetwork& net, const std::string& name) {
  for (std::size_t k = 0; k < net.size(); ++k)
    if (net.solver(k).domain_name() == name) return k;
  ADD_FAILURE() << "no domain " << name;
  return 0;
}

void expect_same_bits(const cosim::LayerNetwork& a, const cosim::LayerNetwork& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto& sa = a.solver(k);
    const auto& sb = b.solver(k);
    EXPECT_EQ(sa.cycle(), sb.cycle()) << what << ", " << sa.domain_name();
    EXPECT_EQ(a.stepper(k).time(), b.stepper(k).time()) << what << ", " << sa.domain_name();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < sa.displacement().size(); ++i) {
      differ += std::bit_cast<std::uint64_t>(sa.displacement()[i]) !=
                std::bit_cast<std::uint64_t>(sb.displacement()[i]);
      differ += std::bit_cast<std::uint64_t>(sa.velocity_mid()[i]) !=
                std::bit_cast<std::uint64_t>(sb.velocity_mid()[i]);
    }
    EXPECT_EQ(differ, 0u) << what << ", " << sa.domain_name() << ": values that differ";
  }
}

/// Restoring `paths` into a network of `options` throws CheckpointError saying `fix`.
void expect_restore_refused(const model::Model& m, const cosim::LayerNetworkOptions& options,
                            const std::vector<std::string>& paths, const std::string& fix) {
  cosim::LayerNetwork wrong(m, options);
  try {
    wrong.restore(paths);
    ADD_FAILURE() << "restored where it should say: " << fix;
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find(fix), std::string::npos) << e.what();
  }
}

}  // namespace

// Every order of the domains in the network (the earliest-first rule then calls them in other
// orders), multi and split; after each pause also an `until` one tick later, which the leader's
// next instant passes: the u_J it sent before the first pause must not carry the old mark.
TEST(LayerVariableCheckpoint, TheChainPausesTogetherAtTheLeadersFirstInstantAfterUntil) {
  std::vector<std::string> names{"coarse", "fine", "mid"};  // sorted: next_permutation
  const std::map<std::string, int> part{{"coarse", 0}, {"mid", 1}, {"fine", 2}};
  int orders = 0;
  do {
    for (const bool split : {false, true}) {
      std::vector<model::Domain> domains;
      for (const auto& n : names) domains.push_back({n, {part.at(n)}});
      const auto m = pulsed_chain3(domains, 2e-3, 2e-4, -1e5);
      auto o = variable();
      o.run.common_step = split;
      cosim::LayerNetwork net(m, o);
      net.initialize();
      const std::size_t leader = index_of(net, "coarse");
      const std::string where = fmt::format("order {} {} {}, {}", names[0], names[1], names[2],
                                            split ? "split" : "multi");
      cosim::Tick leader_before = -1;  // the leader's last sampled instant before the pause
      int pauses = 0;
      auto pause_at = [&](cosim::Tick until) {
        ASSERT_FALSE(net.run(
            [&](std::size_t k) {
              if (k == leader) leader_before = net.stepper(k).time();
            },
            until))
            << where;
        const cosim::Tick T = net.stepper(leader).time();
        EXPECT_GE(T, until) << where;
        EXPECT_LT(leader_before, until) << where << ": the leader passed `until` before pausing";
        for (std::size_t k = 0; k < net.size(); ++k) {
          EXPECT_EQ(net.stepper(k).time(), T)
              << where << ", " << net.solver(k).domain_name() << " at until " << until;
          EXPECT_TRUE(net.stepper(k).at_cycle_boundary()) << where;
        }
        ++pauses;
      };
      for (double until_s = 1.3e-4; until_s < 1.9e-3; until_s += 1.7e-4) {
        pause_at(ticks(net, until_s));
        if (::testing::Test::HasFailure()) return;
        pause_at(net.stepper(leader).time() + 1);  // closer than one step
      }
      EXPECT_EQ(pauses, 22) << where;
      EXPECT_TRUE(net.run()) << where;
    }
    ++orders;
  } while (std::next_permutation(names.begin(), names.end()));
  EXPECT_EQ(orders, 6);
}

TEST(LayerVariableCheckpoint, SavedAndRestoredChainEndsWithTheUninterruptedRunsBits) {
  const auto m = pulsed_chain();
  cosim::LayerNetwork straight(m, variable());
  straight.initialize();
  ASSERT_TRUE(straight.run());

  cosim::LayerNetwork paused(m, variable());
  paused.initialize();
  ASSERT_FALSE(paused.run({}, ticks(paused, 7.7e-4)));  // mid-pulse
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_layer_variable_checkpoint_" + std::to_string(::getpid()));
  const auto paths = crashlink::testing::save_network(paused, dir);
  cosim::LayerNetworkOptions fixed;  // a checkpoint of variable steps restarts no fixed run,
  fixed.step_safety = 0.9;
  expect_restore_refused(m, fixed, paths, "restart with --variable-steps");
  auto other = variable();  // nor one whose leader would choose its steps with another margin,
  other.step_safety = 0.8;
  expect_restore_refused(m, other, paths, "step safety of 0.9");
  auto split = variable();  // nor a split run
  split.run.common_step = true;
  expect_restore_refused(m, split, paths, "restart with --mode multi");
  cosim::LayerNetwork resumed(m, variable());
  resumed.restore(paths);
  for (std::size_t k = 0; k < resumed.size(); ++k)
    EXPECT_EQ(resumed.stepper(k).time(), paused.stepper(k).time());
  ASSERT_TRUE(resumed.run());
  ASSERT_TRUE(paused.run());
  std::filesystem::remove_all(dir);

  expect_same_bits(straight, resumed, "restored");
  expect_same_bits(straight, paused, "paused");
  std::string cycles;
  for (std::size_t k = 0; k < straight.size(); ++k)
    cycles +=
        " " + straight.solver(k).domain_name() + " " + std::to_string(straight.solver(k).cycle());
  std::printf("[measured] chain, variable steps, restored from %.4e s: cycles%s, to the bit\n",
              paused.seconds(ticks(paused, 7.7e-4)), cycles.c_str());
}
