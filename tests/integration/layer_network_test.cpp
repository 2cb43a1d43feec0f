// cosim::LayerNetwork (solver/cosim/layer_network.h): every domain's LayerStepper in one thread
// with fixed nested steps. The steppers are what the daemons run, so these tests pin the
// algorithm in `multi`: (a) a Hann pulse through the bar at ratios 1.5-4 vs mono; (b) three
// domains at three steps vs mono. `split` vs mono: split_mono_test.cpp.
#include "solver/cosim/layer_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/integration/solver.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

struct Accuracy {
  double disp = 0.0, vel = 0.0, refl = 0.0, coupling = 0.0;
  std::int64_t substeps = 0;
};

/// The study's 1-D bar (coupling-study/README.md "Measurements") in metres: fine [0, 1] m
/// (dx = 10 mm), coarse [1, 3] m (elements r dx), nu = 0, far end fixed, Hann velocity pulse of
/// 0.2 m / c on x = 0, bulk viscosity on. Coarse proposal r h: the fine side takes ceil(r) equal
/// substeps (nested_steps.h). Reference: mono at the fine step actually used. `scheme`: "layer",
/// or "lts" with `overlap` further coarse element layers in the fine domain; bulk viscosity off
/// with `bulk_viscosity` false (in mono too).
Accuracy hann_vs_mono(double r, const std::string& scheme = "layer", int overlap = 0,
                      bool bulk_viscosity = true) {
  model::Model m;
  m.name = "bar";
  auto mat = elastic("steel");
  mat.poisson_ratio = 0.0;
  m.materials.push_back(mat);
  const double dx = 0.01;
  const int nc = static_cast<int>(std::lround(2.0 / (r * dx)));
  add_box(m, part("fine", 0), {{0.0, 0.0, 0.0}, {1.0, 0.05, 0.05}, {100, 1, 1}});
  add_box(m, part("coarse", 0), {{1.0, 0.0, 0.0}, {nc * r * dx, 0.05, 0.05}, {nc, 1, 1}});
  finish(m);
  const double xe = 1.0 + nc * r * dx;
  for (auto i : where(m, [&](double x, double, double) { return x > xe - 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  m.controls.end_time_s = 10.0;
  m.controls.bulk_viscosity = bulk_viscosity;
  m.domains = {{"fine", {0}}, {"coarse", {1}}};
  const double c = std::sqrt(mat.youngs_modulus_Pa / mat.density_kg_m3);
  const double unit = 1.0 / c, tp = 0.2 * unit, v0 = 1.0;
  const model::Curve hann = hann_pulse(tp, v0, 10.0);
  m.prescribed_velocities.push_back(
      {"hann", where(m, [](double x, double, double) { return x < 1e-9; }), 0, hann});

  // proposals: the fine mesh's step with a margin, and r times it for the coarse side
  double h0 = 0.0;
  {
    integration::Solver probe(m, "probe");
    probe.initialize();
    h0 = 0.8 * probe.dt_s();  // fixed steps: margin for bulk viscosity under the wave
  }
  cosim::LayerNetworkOptions o;
  o.run.scheme = scheme;
  o.overlap_layers = overlap;
  cosim::LayerNetwork net(m, o);
  const auto& d = net.domains();
  std::size_t kf = 0;
  for (std::size_t k = 0; k < d.solvers.size(); ++k)
    if (d.solvers[k]->domain_name() == "fine") kf = k;
  o.proposal_s.assign(d.solvers.size(), 0.0);
  o.proposal_s[kf] = h0;
  o.proposal_s[1 - kf] = r * h0;
  cosim::LayerNetwork mr(m, o);
  mr.initialize();
  const double h = mr.seconds(mr.plan().step[kf]);
  integration::Solver mono(m, "mono");
  mono.initialize();
  mono.impose_step(h);
  mono.begin_cycle();
  std::size_t gi = 0;
  std::vector<std::size_t> fine_nodes;
  for (std::size_t g = 0; g < m.nodes.count(); ++g) {
    const double x = m.nodes.x0[3 * g];
    if (std::abs(x - 1.0) < 1e-9) gi = g;
    if (x <= 0.9 + 1e-9) fine_nodes.push_back(g);
  }
  const auto& md = mr.domains();
  EXPECT_EQ(md.owner_solver[gi], kf);
  double du = 0.0, umax = 0.0, dv = 0.0, vmax = 0.0, refl = 0.0;
  std::int64_t mono_steps = 0;
  const auto& F = mr.solver(kf);
  auto sample = [&](std::size_t k) {
    if (k != kf) return;
    const std::int64_t n = mr.stepper(kf).time() / mr.plan().step[kf];
    while (mono_steps < n) {
      mono.end_cycle();
      mono.impose_step(h);
      mono.begin_cycle();
      ++mono_steps;
    }
    const double t = mr.seconds(mr.stepper(kf).time()) / unit;
    const std::size_t li = md.owner_local[gi];
    const double u = F.displacement()[3 * li], um = mono.displacement()[3 * gi];
    const double v = F.node_velocity(li)[0], vm = mono.node_velocity(gi)[0];
    if (t <= 4.8) {
      du = std::max(du, std::abs(u - um));
      umax = std::max(umax, std::abs(um));
    }
    if (t <= 2.9) {
      dv = std::max(dv, std::abs(v - vm));
      vmax = std::max(vmax, std::abs(vm));
      for (auto g : fine_nodes)
        refl = std::max(refl,
                        std::abs(F.node_velocity(md.owner_local[g])[0] - mono.node_velocity(g)[0]));
    }
  };
  const auto until = static_cast<coupling::Tick>(4.8 * unit * 1e15);
  mr.run(sample, until);
  Accuracy a;
  a.disp = du / umax;
  a.vel = dv / vmax;
  a.refl = refl / v0;
  a.coupling = mr.energy().coupling_work_J / mr.energy().external_work_J;
  a.substeps = mr.plan().n[kf] / mr.plan().n[1 - kf];
  std::printf(
      "[measured] %s (overlap %d) multi, bulk viscosity %s, Hann pulse, stable-step ratio %.2f "
      "(%lld fine substeps of %.3e s "
      "per coarse step) vs mono at that step: interface displacement error %.2f %%, interface "
      "velocity error %.2f %%, reflection %.2f %% of v0; summed coupling work %.2e of the input\n",
      scheme.c_str(), overlap, bulk_viscosity ? "on" : "off", r, static_cast<long long>(a.substeps),
      h, 100.0 * a.disp, 100.0 * a.vel, 100.0 * a.refl, a.coupling);
  return a;
}

}  // namespace

// The bar bounds for ratios up to 4 (3 % / 7 % / 10 %), non-integer ratios included.
TEST(LayerNetwork, HannPulseAccuracyVsMonoAllRatiosUpToFour) {
  for (double r : {1.5, 2.0, 2.5, 3.0, 4.0}) {
    const auto a = hann_vs_mono(r);
    EXPECT_LE(a.disp, 0.03) << "r = " << r;
    EXPECT_LE(a.vel, 0.07) << "r = " << r;
    EXPECT_LE(a.refl, 0.10) << "r = " << r;
    EXPECT_LE(std::abs(a.coupling), 0.01) << "r = " << r;
  }
}

// lts (issue #25): the same bar, no interface damping, at least as accurate as `layer` in all
// three measures at every ratio up to 4, with one and two overlap layers, with bulk viscosity on
// (as the test above) and off. The elements on J compute none under lts
// (Solver::set_ghost_bulk_viscosity): with it, the ghosts' reflected-path velocity drove a viscous
// force that pumped energy (interface displacement 4.9 % off mono at r = 1.5, coupling work up to
// 10^2 times the input; docs/multirate.md "lts").
TEST(LtsNetwork, HannPulseAtLeastAsAccurateAsLayer) {
  for (bool bulk : {true, false})
    for (double r : {1.5, 2.0, 2.5, 3.0, 4.0}) {
      const auto l = hann_vs_mono(r, "layer", 0, bulk);
      for (int ov : {1, 2}) {
        const auto a = hann_vs_mono(r, "lts", ov, bulk);
        const auto where = "r = " + std::to_string(r) + ", overlap " + std::to_string(ov) +
                           ", bulk viscosity " + (bulk ? "on" : "off");
        EXPECT_LE(a.disp, l.disp) << where;
        EXPECT_LE(a.vel, l.vel) << where;
        EXPECT_LE(a.refl, l.refl) << where;
        EXPECT_LE(std::abs(a.coupling), 0.1) << where;
      }
    }
}

namespace {

void fix_nodes(model::Model& m, const std::vector<std::int32_t>& nodes, std::uint8_t mask) {
  for (auto i : nodes) m.fixed[static_cast<std::size_t>(i)] |= mask;
}

/// `multi` at the domains' own (nested) steps vs mono at the finest of them: max over the base
/// instants of max|u_multi - u_mono| / max|u_mono| (every domain lands on the base instants).
double multi_vs_mono(const model::Model& m, const std::string& label, int base_periods,
                     std::vector<coupling::Tick>* steps) {
  cosim::LayerNetworkOptions o;
  o.step_safety = 0.8;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  *steps = net.plan().step;
  const auto h_min = *std::min_element(steps->begin(), steps->end());
  integration::Solver mono(m, "mono");
  mono.initialize();
  mono.impose_step(net.seconds(h_min));
  mono.begin_cycle();
  const auto& d = net.domains();
  double worst = 0.0, scale = 0.0;
  for (int k = 1; k <= base_periods; ++k) {
    const coupling::Tick T = k * net.plan().base;
    net.run({}, T);  // every domain paused at T (u(T) known, cycle not begun)
    while (mono.time_s() < net.seconds(T) - 0.5 * net.seconds(h_min)) {
      mono.end_cycle();
      mono.impose_step(net.seconds(h_min));
      mono.begin_cycle();
    }
    const auto u = net.global_displacement();
    for (std::size_t i = 0; i < u.size(); ++i) {
      scale = std::max(scale, std::abs(mono.displacement()[i]));
      worst = std::max(worst, std::abs(u[i] - mono.displacement()[i]));
    }
  }
  std::string st;
  for (std::size_t k = 0; k < steps->size(); ++k)
    st += " " + d.solvers[k]->domain_name() + " " + std::to_string(net.seconds((*steps)[k]));
  std::printf(
      "[measured] layer multi vs mono, %s, steps [s]:%s; %d base periods: max|du|/max|u| "
      "= %.3e\n",
      label.c_str(), st.c_str(), base_periods, worst / scale);
  return worst / scale;
}

}  // namespace

// Three domains, three steps (ratio 1 : 2 : 4), against mono at the finest step.
TEST(LayerNetwork, ThreeDomainsThreeStepsMatchMono) {
  {
    auto m = chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}});
    m.controls.end_time_s = 1.0;
    m.controls.bulk_viscosity = true;
    fix_nodes(m, where(m, [](double x, double, double) { return x < 1e-9; }), 7);
    const auto end = where(m, [](double x, double, double) { return x > 2.0 - 1e-9; });
    m.loads.push_back({"pulse", end, 0, model::Curve{{0.0, 2e-4, 4e-4}, {0.0, -1e5, 0.0}}});
    m.loads.push_back({"pulse2", end, 1, model::Curve{{0.0, 2e-4, 4e-4}, {0.0, 2e4, 0.0}}});
    std::vector<coupling::Tick> steps;
    const double e = multi_vs_mono(m, "chain 0.2 | 0.1 | 0.05 m", 400, &steps);
    std::sort(steps.begin(), steps.end());
    EXPECT_EQ(steps[1], 2 * steps[0]);
    EXPECT_EQ(steps[2], 4 * steps[0]);
    EXPECT_LE(e, 0.03);
  }
  {
    auto m = quadrants3();
    m.controls.end_time_s = 1.0;
    m.controls.bulk_viscosity = true;
    fix_nodes(m, where(m, [](double x, double, double) { return x < -0.5 + 1e-9; }), 63);
    const auto edge = where(m, [](double x, double, double) { return x > 0.5 - 1e-9; });
    m.loads.push_back({"pulse", edge, 0, model::Curve{{0.0, 5e-4, 1e-3}, {0.0, 1e3, 0.0}}});
    m.loads.push_back({"pulse2", edge, 1, model::Curve{{0.0, 5e-4, 1e-3}, {0.0, -5e2, 0.0}}});
    std::vector<coupling::Tick> steps;
    // The difference grows linearly in time (phase drift: mono runs the heavy quadrants at a
    // quarter of their own Courant number), not exponentially: 50 base periods (2.3 ms, some 20
    // wave crossings) within the bound, doubling the time at most doubles it (+25 %).
    const double e50 =
        multi_vs_mono(m, "three shell quadrant domains meeting at a node", 50, &steps);
    const double e300 =
        multi_vs_mono(m, "three shell quadrant domains meeting at a node", 300, &steps);
    const double e600 =
        multi_vs_mono(m, "three shell quadrant domains meeting at a node", 600, &steps);
    EXPECT_LE(e50, 0.03);
    EXPECT_LE(e600 / e300, 2.5);
  }
}

// A chain fine | mid | coarse whose end time is not a coarse instant: every domain ends at the
// first coarse instant after it (the end rounded up to the base period, LayerStepper::
// set_end_time). Before, the fine domain ended at the first mid instant after the end time while
// mid went on to the next coarse instant and waited for the fine domain's force forever.
TEST(LayerNetwork, AChainEndsTogetherWhateverTheEndTime) {
  for (const double end : {1.0e-4, 1.37e-4, 2.11e-4, 3.3e-4}) {
    auto m = chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}});
    m.controls.end_time_s = end;
    cosim::LayerNetworkOptions o;
    o.step_safety = 0.8;
    cosim::LayerNetwork net(m, o);
    net.initialize();
    ASSERT_TRUE(net.run()) << "end " << end;
    const coupling::Tick t = net.stepper(0).time();
    EXPECT_EQ(t % net.plan().base, 0) << "end " << end;
    EXPECT_GE(net.seconds(t), end * (1.0 - 1e-12)) << "end " << end;
    EXPECT_LT(net.seconds(t - net.plan().base), end) << "end " << end;
    for (std::size_t k = 1; k < net.size(); ++k)
      EXPECT_EQ(net.stepper(k).time(), t) << "end " << end << ", domain " << k;
  }
}

// The run's configuration names the scheme: a network asked to run another one refuses.
TEST(LayerNetwork, RefusesAConfigurationForAnotherScheme) {
  const auto m = chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}});
  cosim::LayerNetworkOptions o;
  o.run.scheme = "paper";
  try {
    cosim::LayerNetwork net(m, o);
    FAIL() << "a `paper` configuration ran as `layer`";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("not 'paper'"), std::string::npos) << e.what();
  }
}

// The coarse sides send u_J(T + H) ahead of their nodal passes (LayerStepper, Solver::
// predict_next_positions) at every coarse step but their first, in a chain where the middle
// domain is the coarse side of one interface and the fine side of the other, and on shells
// whose J nodes rotate; the passes then agree to the bit (the stepper checks it: a difference
// would have thrown).
TEST(LayerNetwork, CoarseSidesSendUJAheadOfTheirNodalPasses) {
  for (int shape = 0; shape < 2; ++shape) {
    auto m = shape == 0 ? chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}}) : quadrants3();
    m.controls.end_time_s = shape == 0 ? 1e-3 : 5e-4;
    m.controls.bulk_viscosity = true;
    if (shape == 0) {
      fix_nodes(m, where(m, [](double x, double, double) { return x < 1e-9; }), 7);
      const auto end = where(m, [](double x, double, double) { return x > 2.0 - 1e-9; });
      m.loads.push_back({"pulse", end, 0, model::Curve{{0.0, 2e-4, 4e-4}, {0.0, -1e5, 0.0}}});
    } else {
      fix_nodes(m, where(m, [](double x, double, double) { return x < -0.5 + 1e-9; }), 63);
      const auto edge = where(m, [](double x, double, double) { return x > 0.5 - 1e-9; });
      m.loads.push_back({"pulse", edge, 2, model::Curve{{0.0, 5e-4, 1e-3}, {0.0, 1e3, 0.0}}});
    }
    cosim::LayerNetworkOptions o;
    o.step_safety = 0.8;  // fixed steps: margin for the viscosity under the pulse
    cosim::LayerNetwork net(m, o);
    net.initialize();
    ASSERT_TRUE(net.run());
    std::int64_t ahead = 0;
    for (std::size_t k = 0; k < net.size(); ++k) {
      const auto& st = net.stepper(k);
      std::int64_t coarse_ports = 0;
      bool rotates = false;
      for (const auto& port : st.ports()) {
        if (port.fine_side) continue;
        ++coarse_ports;
        for (auto l : port.local) rotates = rotates || st.solver().inertia()[l] > 0.0;
      }
      EXPECT_EQ(st.displacements_sent_ahead(), st.displacements_sent() - coarse_ports)
          << "shape " << shape << ", domain " << st.solver().domain_name();
      if (shape == 1 && coarse_ports > 0) {
        EXPECT_TRUE(rotates);
      }
      ahead += st.displacements_sent_ahead();
    }
    EXPECT_GT(ahead, 20) << "shape " << shape;
    std::printf("shape %d: %lld u_J messages sent ahead\n", shape, static_cast<long long>(ahead));
  }
}
