// `split` vs `mono` for the `layer` scheme (docs/design.md §2.7, "How to distribute layer"): the
// global model cut by partition::decompose(global, Layer) and run by cosim::SplitRunner (one Solver
// per domain, coupled through J at a common step, [8] of Bourel 2005) must reproduce the same model
// run by one Solver at the same step (mono) to round-off: max |u_split - u_mono| / max |u_mono|
// <= 1e-10 after 10^4 steps. At a common step the layer cycle is the central-difference cycle
// ([1], [2]) with its element loop cut in pieces, so only summation order differs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "tests/integration/network_vs_mono.h"
#include "tests/support/split_runner.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

constexpr int kCycles = 10000;

struct Comparison {
  double max_rel_diff = 0.0;  ///< max |u_split - u_mono| / max |u_mono| over every global dof
  double u_scale = 0.0;       ///< max |u_mono| [m]
  double split_total_J = 0.0, mono_total_J = 0.0;
  double split_balance = 0.0, mono_balance = 0.0;  ///< balance_error()
  double coupling_work_J = 0.0, external_work_J = 0.0;
  std::size_t domains = 0, interfaces = 0;
  double network_rel_diff = 0.0;  ///< the same for cosim::LayerNetwork (fixed common step)
  double network_total_J = 0.0, network_mono_total_J = 0.0;
};

/// Runs `global` split and mono at the split's common step for `cycles` steps and compares.
Comparison split_vs_mono(const model::Model& global, const std::string& label,
                         int cycles = kCycles) {
  cosim::SplitRunner split(global);
  integration::Solver mono(global, "mono");
  split.initialize();
  mono.initialize();
  mono.impose_step(split.dt_s());
  for (int n = 0; n < cycles; ++n) {
    split.begin_cycle();
    mono.begin_cycle();
    split.end_cycle();
    mono.end_cycle();
    mono.impose_step(split.dt_s());  // the same step sequence (mono's own proposal is the same min)
  }
  // Energies are complete at t^n after begin_cycle() (solver.h).
  split.begin_cycle();
  mono.begin_cycle();
  Comparison c;
  const auto u = split.global_displacement();
  const auto& um = mono.displacement();
  EXPECT_EQ(u.size(), um.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < u.size() && i < um.size(); ++i) {
    c.u_scale = std::max(c.u_scale, std::abs(um[i]));
    worst = std::max(worst, std::abs(u[i] - um[i]));
  }
  EXPECT_GT(c.u_scale, 0.0) << label;
  c.max_rel_diff = c.u_scale > 0.0 ? worst / c.u_scale : 0.0;
  const auto& es = split.energy();
  const auto& em = mono.energy();
  c.split_total_J = es.total_J();
  c.mono_total_J = em.total_J();
  c.split_balance = es.balance_error();
  c.mono_balance = em.balance_error();
  c.coupling_work_J = es.coupling_work_J;
  c.external_work_J = em.external_work_J + em.initial_total_J;
  c.domains = split.solver_count();
  c.interfaces = split.decomposition().interfaces.size();
  const auto nm = network_vs_mono(global, cycles);
  c.network_rel_diff = nm.rel_diff;
  c.network_total_J = nm.total_J;
  c.network_mono_total_J = nm.mono_total_J;
  std::printf(
      "[measured] layer network (common fixed step) vs mono, %s, %d steps: max |du|/max|u| "
      "= %.3e; energy %.9e J vs %.9e J\n",
      label.c_str(), cycles, c.network_rel_diff, c.network_total_J, c.network_mono_total_J);
  std::printf(
      "[measured] split vs mono, %s, %d steps of %.3e s, %zu domains, %zu interfaces: "
      "max |du|/max|u| = %.3e (max|u| = %.3e m); energy split %.9e J mono %.9e J "
      "(rel diff %.2e); summed coupling work %.2e J of input %.3e J; balance error "
      "split %.2e mono %.2e\n",
      label.c_str(), cycles, split.dt_s(), c.domains, c.interfaces, c.max_rel_diff, c.u_scale,
      c.split_total_J, c.mono_total_J,
      std::abs(c.split_total_J - c.mono_total_J) / std::max(std::abs(c.mono_total_J), 1e-300),
      c.coupling_work_J, c.external_work_J, c.split_balance, c.mono_balance);
  return c;
}

void expect_reproduces(const Comparison& c) {
  EXPECT_LE(c.max_rel_diff, 1e-10);
  EXPECT_LE(c.network_rel_diff, 1e-10);
  EXPECT_NEAR(c.network_total_J, c.network_mono_total_J, 1e-9 * std::abs(c.network_mono_total_J));
  EXPECT_NEAR(c.split_total_J, c.mono_total_J, 1e-9 * std::abs(c.mono_total_J));
  // The domains' coupling works cancel in the sum: what F does on J, C receives.
  EXPECT_LE(std::abs(c.coupling_work_J), 1e-8 * c.external_work_J);
  EXPECT_LE(std::abs(c.split_balance - c.mono_balance), 1e-6);
}

/// A pulse of `force` N per node in dof `dof` on `nodes`: constant for 20 us, or (`ramp_s` > 0)
/// a triangle rising over ramp_s and falling over ramp_s (for steps longer than 20 us).
void pulse(model::Model& m, const std::vector<std::int32_t>& nodes, int dof, double force,
           double ramp_s = 0.0) {
  if (ramp_s > 0.0)
    m.loads.push_back(
        {"pulse", nodes, dof, model::Curve{{0.0, ramp_s, 2.0 * ramp_s}, {0.0, force, 0.0}}});
  else
    m.loads.push_back(
        {"pulse", nodes, dof, model::Curve{{0.0, 2e-5, 2.1e-5}, {force, force, 0.0}}});
}

void fix(model::Model& m, const std::vector<std::int32_t>& nodes, std::uint8_t mask) {
  for (auto i : nodes) m.fixed[static_cast<std::size_t>(i)] |= mask;
}

void long_run(model::Model& m) {
  m.controls.end_time_s = 1.0;  // the cycle count ends the run
  m.controls.bulk_viscosity = true;
}

}  // namespace

/// The bar of (a), unloaded and unconstrained.
model::Model bar_two_parts() {
  model::Model m;
  m.name = "bar";
  m.materials.push_back(elastic("steel"));
  add_box(m, part("coarse", 0), {{0.0, 0.0, 0.0}, {0.1, 0.01, 0.01}, {10, 1, 1}});
  add_box(m, part("fine", 0), {{0.1, 0.0, 0.0}, {0.05, 0.01, 0.01}, {10, 1, 1}});
  finish(m);
  long_run(m);
  m.domains = {{"coarse", {0}}, {"fine", {1}}};
  return m;
}

// (a) A bar 10 x 10 mm: part "coarse" 10 hexes of 10 mm (x in [0, 0.1]), part "fine" 10 hexes of
// 5 mm (x in [0.1, 0.15]), clamped at x = 0.15, a pulse on the end x = 0; bulk viscosity on.
TEST(SplitMono, BarOfTwoElementSizes) {
  auto m = bar_two_parts();
  for (auto i : where(m, [](double x, double, double) { return x > 0.15 - 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  pulse(m, where(m, [](double x, double, double) { return x < 1e-9; }), 0, 1e3);
  const auto c = split_vs_mono(m, "bar 10 mm | 5 mm");
  EXPECT_EQ(c.domains, 2u);
  expect_reproduces(c);
}

// (a') The same bar free, set moving by a non-uniform initial velocity field, under gravity: the
// ghost J has no weight in the fine domain (its mass is the owner's, which applies M_J g).
TEST(SplitMono, BarWithInitialVelocityFieldAndGravity) {
  auto m = bar_two_parts();
  m.controls.gravity_m_s2 = {0.0, -9.81, 3.0};
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double x = m.nodes.x0[3 * i], y = m.nodes.x0[3 * i + 1];
    m.initial_velocities.push_back(
        {{static_cast<std::int32_t>(i)},
         {2.0 * std::sin(20.0 * x), 0.5 * std::cos(30.0 * x) + 40.0 * y, 0.3 * x}});
  }
  const auto c = split_vs_mono(m, "bar 10 mm | 5 mm, initial velocity field, gravity");
  expect_reproduces(c);
}

// (b) A shell plate 1 x 1 m, 2 mm, cut along x = 0.5: "left" 4 x 8 shells (0.125 m), "right"
// 8 x 8 (0.0625 x 0.125 m), clamped on x = 0 (6 dofs), in-plane pulse on the free edge x = 1
// (membrane: translations only cross J).
TEST(SplitMono, ShellPlateCutInPlaneLoad) {
  auto m = plate_cut();
  long_run(m);
  fix(m, where(m, [](double x, double, double) { return x < 1e-9; }), 63);
  const auto edge = where(m, [](double x, double, double) { return x > 1.0 - 1e-9; });
  pulse(m, edge, 0, 1e3);
  pulse(m, edge, 1, 5e2);
  const auto c = split_vs_mono(m, "shell plate, in-plane pulse");
  expect_reproduces(c);
}

// (b') The same plate loaded out of plane. Bending turns J: the layer's moment on J and J's
// angular velocity cross the interface too.
TEST(SplitMono, ShellPlateCutOutOfPlaneLoad) {
  auto m = plate_cut();
  long_run(m);
  fix(m, where(m, [](double x, double, double) { return x < 1e-9; }), 63);
  pulse(m, where(m, [](double x, double, double) { return x > 1.0 - 1e-9; }), 2, 10.0);
  const auto c = split_vs_mono(m, "shell plate, out-of-plane pulse");
  expect_reproduces(c);
}

// (c) A hex block: "coarse" 2 x 2 x 2 hexes of 0.5 m, "fine" 4 x 2 x 2 (0.125 x 0.5 x 0.5 m),
// clamped at x = 0, an oblique triangular pulse (0.5 ms up, 0.5 ms down) on the fine end face.
TEST(SplitMono, HexBlockOfTwoParts) {
  auto m = hex_block();
  long_run(m);
  fix(m, where(m, [](double x, double, double) { return x < 1e-9; }), 7);
  const auto end = where(m, [](double x, double, double) { return x > 1.5 - 1e-9; });
  pulse(m, end, 0, 1e5, 5e-4);
  pulse(m, end, 2, 5e4, 5e-4);
  const auto c = split_vs_mono(m, "hex block 0.5 m | 0.125 m");
  expect_reproduces(c);
}

// (d) Three domains in a chain, element lengths 0.2 / 0.1 / 0.05 m: "mid" is fine at its
// interface with "coarse" and coarse at its interface with "fine". Domains listed fine first so
// that the processing order must come from the ownership, not from the file.
TEST(SplitMono, ThreeDomainChain) {
  auto m = chain3({{"fine", {2}}, {"coarse", {0}}, {"mid", {1}}});
  long_run(m);
  fix(m, where(m, [](double x, double, double) { return x < 1e-9; }), 7);
  const auto end = where(m, [](double x, double, double) { return x > 2.0 - 1e-9; });
  pulse(m, end, 0, -1e5);
  pulse(m, end, 1, 2e4);
  cosim::SplitRunner probe(m);
  ASSERT_EQ(probe.solver_count(), 3u);
  ASSERT_EQ(probe.decomposition().interfaces.size(), 2u);
  std::vector<std::string> order;
  for (auto k : probe.order()) order.push_back(probe.solver(k).domain_name());
  EXPECT_EQ(order, (std::vector<std::string>{"coarse", "mid", "fine"}));
  const auto c = split_vs_mono(m, "chain 0.2 | 0.1 | 0.05 m");
  expect_reproduces(c);
}

// (d') Three domains meeting at one node: four shell quadrants with steps in ratio 1 : 2 : 4
// (densities 1, 4, 16 x steel), the centre node a ghost in two domains and owned by the third;
// clamped on the outer edge x = -0.5, in-plane pulse on x = 0.5 (membrane, see (b')).
TEST(SplitMono, ThreeDomainsAtOneNodeInPlane) {
  auto m = quadrants3();
  long_run(m);
  fix(m, where(m, [](double x, double, double) { return x < -0.5 + 1e-9; }), 63);
  const auto edge = where(m, [](double x, double, double) { return x > 0.5 - 1e-9; });
  pulse(m, edge, 0, 1e3);
  pulse(m, edge, 1, -5e2);
  const auto c = split_vs_mono(m, "three shell quadrant domains, in-plane pulse");
  EXPECT_EQ(c.domains, 3u);
  expect_reproduces(c);
}
