// cosim::LayerNetwork (solver/cosim/layer_network.h): every domain's LayerStepper in one thread
// with fixed nested steps. The steppers are what the daemons run, so these tests pin the
// algorithm: (a) at an integer ratio it is MultirateRunner's cycle to the bit; (b) at a common step
// it reproduces mono at the same step; (c) three domains at three steps run and match mono.
#include "solver/cosim/layer_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/cosim/multirate_runner.h"
#include "solver/integration/solver.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

/// A bar of hexes: part "fine" (dx) on [0, lf], part "coarse" (r dx) after it; far end fixed,
/// a force pulse on x = 0 and a compressive initial velocity field.
model::Model pulse_bar(double r, double lf = 0.2, double lc = 0.4) {
  model::Model m;
  m.name = "bar";
  m.materials.push_back(elastic("steel"));
  const double dx = 0.01;
  const int nf = static_cast<int>(std::lround(lf / dx));
  const int nc = static_cast<int>(std::lround(lc / (r * dx)));
  add_box(m, part("fine", 0), {{0.0, 0.0, 0.0}, {lf, 0.05, 0.05}, {nf, 1, 1}});
  add_box(m, part("coarse", 0), {{lf, 0.0, 0.0}, {nc * r * dx, 0.05, 0.05}, {nc, 1, 1}});
  finish(m);
  const double xe = lf + nc * r * dx;
  for (auto i : where(m, [&](double x, double, double) { return x > xe - 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  m.loads.push_back({"pulse", where(m, [](double x, double, double) { return x < 1e-9; }), 0,
                     model::Curve{{0.0, 2e-5, 2.1e-5}, {1e4, 1e4, 0.0}}});
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    m.initial_velocities.push_back(
        {{static_cast<std::int32_t>(i)}, {-0.5 * m.nodes.x0[3 * i] / xe, 0.1, 0.0}});
  m.controls.end_time_s = 10.0;
  m.controls.bulk_viscosity = true;
  m.domains = {{"fine", {0}}, {"coarse", {1}}};
  return m;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b, double* scale) {
  double worst = 0.0, s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    s = std::max(s, std::abs(b[i]));
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  if (scale) *scale = s;
  return worst;
}

}  // namespace

// (a) The stepper network and the two-domain runner are the same algorithm: bit-identical.
TEST(LayerNetwork, IntegerRatioIsMultirateRunnerToTheBit) {
  for (int r : {1, 2, 4}) {
    const auto m = pulse_bar(r);
    cosim::MultirateOptions mo;
    mo.ratio_p = r;
    mo.ratio_q = 1;
    mo.step_safety = 0.9;
    cosim::MultirateRunner mr(m, mo);
    mr.initialize();
    cosim::LayerNetworkOptions no;
    no.proposal_s.resize(2);
    for (std::size_t k = 0; k < 2; ++k)  // the runner's steps as proposals
      no.proposal_s[k] = mr.fine().domain_name() == "fine"
                             ? (k == 0 ? mr.fine_dt_s() : mr.coarse_dt_s())
                             : (k == 0 ? mr.coarse_dt_s() : mr.fine_dt_s());
    cosim::LayerNetwork net(m, no);
    net.initialize();
    ASSERT_EQ(net.plan().step[0] * net.plan().n[0], net.plan().base);
    const int coarse_steps = 3000 / r;
    for (int n = 0; n < coarse_steps; ++n) mr.advance();
    const coordinator::Tick until = mr.coarse_time_ticks();
    EXPECT_FALSE(net.run({}, until));
    double scale = 0.0;
    const double d = max_abs_diff(net.global_displacement(), mr.global_displacement(), &scale);
    std::printf(
        "[measured] layer network vs multirate runner, r = %d, %d coarse steps: max|du| = "
        "%.3e m of max|u| = %.3e m\n",
        r, coarse_steps, d, scale);
    EXPECT_GT(scale, 0.0);
    EXPECT_EQ(d, 0.0) << "r = " << r;
  }
}
