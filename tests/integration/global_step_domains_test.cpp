// The global stable step (Controls::global_stable_step) in a cut model: each domain estimates
// its own sub-assembly (its own lumped masses, its ghost nodes in), so its step bounds what the
// mesh allows there. On the three-level bar (scenarios/bar_three_levels.yaml: 2.5, 5 and 10 mm
// hexes, unequal meshes across both interfaces), with the domains listed in either order:
// every domain's planned step at least the element estimate's, the run stable with a clean
// energy balance, and the same displacements as the element-step run within 2 % RMS.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "coupling/ticks.h"
#include "solver/cosim/layer_network.h"
#include "solver/io/scenario_reader.h"

using namespace crashlink;

namespace {

struct Outcome {
  std::vector<std::string> names;
  std::vector<double> dt_s;
  double balance_error = 0.0;
  std::vector<double> u;
};

Outcome run(bool global, bool reversed) {
  auto m =
      io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/bar_three_levels.yaml");
  m.controls.end_time_s = 2.0e-4;
  m.controls.global_stable_step = global;
  if (reversed) std::reverse(m.domains.begin(), m.domains.end());
  cosim::LayerNetworkOptions o;
  o.step_safety = 0.9;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  EXPECT_TRUE(net.run());
  Outcome r;
  const coupling::TickClock clock(o.run.ticks_per_second);
  for (std::size_t k = 0; k < net.size(); ++k) {
    r.names.push_back(net.solver(k).domain_name());
    r.dt_s.push_back(clock.to_seconds(net.plan().step[k]));
  }
  const auto e = net.energy();
  r.balance_error = std::abs(e.balance_error());
  r.u = net.global_displacement();
  return r;
}

double step_of(const Outcome& r, const std::string& name) {
  for (std::size_t k = 0; k < r.names.size(); ++k)
    if (r.names[k] == name) return r.dt_s[k];
  ADD_FAILURE() << "no domain " << name;
  return 0.0;
}

}  // namespace

TEST(GlobalStepDomains, EachDomainStepsAtLeastAsFarAndTheRunStaysClean) {
  for (const bool reversed : {false, true}) {
    const Outcome element = run(false, reversed), global = run(true, reversed);
    for (const char* d : {"fine", "middle", "coarse"}) {
      EXPECT_GE(step_of(global, d), step_of(element, d) * (1.0 - 1e-12))
          << d << (reversed ? " (domains listed coarse first)" : "");
    }
    EXPECT_LT(global.balance_error, 1e-3) << (reversed ? "reversed" : "as written");
    // the same wave: displacements (RMS over the nodes) within 2 % (the front is sharp: the
    // steps change its dispersion, pointwise up to 3.5 % of the largest displacement)
    double norm = 0.0, diff = 0.0;
    ASSERT_EQ(global.u.size(), element.u.size());
    for (std::size_t i = 0; i < global.u.size(); ++i) {
      norm += element.u[i] * element.u[i];
      diff += (global.u[i] - element.u[i]) * (global.u[i] - element.u[i]);
    }
    ASSERT_GT(norm, 0.0);
    std::printf("[measured] %s: RMS difference %.4f of the element-step run's\n",
                reversed ? "coarse first" : "as written", std::sqrt(diff / norm));
    EXPECT_LT(std::sqrt(diff / norm), 0.02) << (reversed ? "reversed" : "as written");
  }
}
