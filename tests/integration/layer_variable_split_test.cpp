// `split` with variable steps (cosim::LayerSteps::VariableCommon, layer_stepper.h "Variable
// common"): every domain at the least proposal of all at every instant, as a mono run takes its
// step. Checked against mono stepping by the same rule (its own proposal floored to whole ticks at
// every cycle and held as LayerStepper holds the common step, integration::kStepHold, to the first
// instant at or after the end time), on the chain coarse | mid | fine, where mid holds ghosts of
// coarse and has fine's: the least proposal, fine's, reaches coarse only through mid's g_A. A pulse
// with bulk viscosity makes the stable step move.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

TEST(LayerVariableSplit, ChainFollowsTheLeastProposalOfAllAsMonoDoes) {
  const auto m = pulsed_chain3({{"coarse", {0}}, {"mid", {1}}, {"fine", {2}}}, 1.5e-3, 1e-4, -4e7);
  cosim::LayerNetworkOptions o;
  o.run.common_step = true;
  o.run.variable_steps = true;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  std::set<cosim::Tick> steps;
  std::size_t leader = 0;
  for (std::size_t k = 0; k < net.size(); ++k)
    if (net.solver(k).domain_name() == "coarse") leader = k;
  ASSERT_TRUE(net.run([&](std::size_t k) {
    if (k == leader) steps.insert(net.stepper(k).step());
  }));

  const double tps = static_cast<double>(net.stepper(0).ticks_per_second());
  integration::Solver mono(m, "mono");
  mono.initialize();
  std::int64_t n = 0;
  double held = 0.0;  // ticks: the step in force, held as mono holds its own
  for (;; ++n) {
    const double proposal = std::floor(mono.dt_s() * tps);  // the daemons' proposal in ticks
    held = integration::held_step(proposal, held);
    mono.impose_step(held / tps);
    mono.begin_cycle();
    if (mono.finished()) break;
    mono.end_cycle();
  }
  const auto u = net.global_displacement();
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    scale = std::max(scale, std::abs(mono.displacement()[i]));
    worst = std::max(worst, std::abs(u[i] - mono.displacement()[i]));
  }
  for (std::size_t k = 0; k < net.size(); ++k) {
    EXPECT_EQ(net.solver(k).cycle(), n) << net.solver(k).domain_name();
    EXPECT_NEAR(net.solver(k).time_s(), mono.time_s(), 1e-15) << net.solver(k).domain_name();
  }
  std::printf(
      "[measured] layer split, variable steps, chain of three: %lld cycles, %zu different steps "
      "(%.4e to %.4e s), to t = %.4e s; max |u - u_mono| / max |u| = %.2e\n",
      static_cast<long long>(n), steps.size(), static_cast<double>(*steps.begin()) / tps,
      static_cast<double>(*steps.rbegin()) / tps, mono.time_s(), worst / scale);
  EXPECT_GT(steps.size(), 10u) << "the step must move for this to test anything";
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(worst / scale, 1e-10);
}
