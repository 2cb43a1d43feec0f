// The `lts` coupling (leapfrog local time stepping, Diaz & Grote 2009, physical-state form;
// layer_stepper.h LayerForm, docs/multirate.md "lts") in process (LayerNetwork), issue #25:
//   - at a step ratio of 1 and no overlap it is the `layer` scheme to the bit (p = 1: the ghosts
//     land on the owner's positions, the hat is the force at the instant itself);
//   - linear elastic free vibration (the stability set-up of studies/free_vibration.h with no bulk
//     viscosity, no interface damping, the velocities scaled down 1e6 so that the geometric
//     nonlinearity is below 1e-9): its discrete energy E^{k-1/2} (cosim::LtsEnergy, summed over
//     the domains) stays within 1e-6 of its first value at every step ratio of the issue, and the
//     physical energy (kinetic + internal) shows no growth.
// CI runs 2 10^4 fine steps per ratio; CRASHLINK_LONG=1 runs the issue's 10^5.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "core/state_archive.h"
#include "solver/cosim/layer_network.h"
#include "solver/io/scenario_reader.h"
#include "studies/free_vibration.h"
#include "tests/integration/network_helpers.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;

namespace {

using studies::FreeVibrationShape;

model::Model linear_model(FreeVibrationShape s, double r) {
  studies::FreeVibrationConfig cfg;
  cfg.damping = {0.0, 1};
  cfg.uniaxial = s == FreeVibrationShape::Bar;
  auto m = studies::free_vibration_model(s, r, cfg);
  m.controls.bulk_viscosity = false;
  m.controls.shell_bulk_viscosity = false;
  for (auto& iv : m.initial_velocities)
    for (double& v : iv.velocity_m_s) v *= 1e-6;  // linear: strains ~1e-10
  return m;
}

/// studies::free_vibration_options (fine proposal 0.8 of mono's step, coarse r times it, step
/// safety 0.9); sweeps change the fine factor (CRASHLINK_LTS_C) and the step safety
/// (CRASHLINK_LTS_SAFETY).
cosim::LayerNetworkOptions options(const model::Model& m, double r, const std::string& scheme,
                                   int overlap) {
  const char* c = std::getenv("CRASHLINK_LTS_C");
  const char* safety = std::getenv("CRASHLINK_LTS_SAFETY");
  return studies::free_vibration_options(m, r, scheme, c ? std::atof(c) : 0.8,
                                         safety ? std::atof(safety) : 0.9, overlap);
}

struct LtsRun {
  double ratio = 0.0;          ///< planned H / h
  double e_drift = 0.0;        ///< max |E/E0 - 1| of the conserved energy
  double phys_lo = 0.0;        ///< min (KE + IE) / its first value - 1
  double phys_hi = 0.0;        ///< max
  double phys_late_hi = 0.0;   ///< max over the last half
  double phys_early_hi = 0.0;  ///< max over the first half
  std::int64_t samples = 0;
};

LtsRun run_lts(FreeVibrationShape s, double r, std::int64_t fine_steps, int overlap) {
  const auto m = linear_model(s, r);
  cosim::LayerNetwork net(m, options(m, r, "lts", overlap));
  net.initialize();
  const auto& plan = net.plan();
  const auto h_min = *std::min_element(plan.step.begin(), plan.step.end());
  const auto h_max = *std::max_element(plan.step.begin(), plan.step.end());
  LtsRun out;
  out.ratio = static_cast<double>(h_max) / static_cast<double>(h_min);
  const coupling::Tick t_end = fine_steps * h_min;
  double e0 = 0.0, p0 = 0.0, phys = 0.0;
  std::size_t count = 0;
  net.run(
      [&](std::size_t k) {
        const coupling::Tick t = net.stepper(k).time();
        if (t % plan.base != 0) return;
        const auto& e = net.solver(k).energy();
        phys += e.total_J();  // kinetic + internal + hourglass (no contact here)
        if (++count < net.size()) return;
        count = 0;
        const double sum = phys;
        phys = 0.0;
        const double E = net.lts_energy_J();
        if (!std::isfinite(E)) return;
        if (out.samples++ == 0) {
          e0 = E;
          p0 = sum;
        }
        out.e_drift = std::max(out.e_drift, std::abs(E / e0 - 1.0));
        const double x = sum / p0 - 1.0;
        out.phys_lo = std::min(out.phys_lo, x);
        out.phys_hi = std::max(out.phys_hi, x);
        if (t >= t_end / 2)
          out.phys_late_hi = std::max(out.phys_late_hi, x);
        else
          out.phys_early_hi = std::max(out.phys_early_hi, x);
      },
      t_end);
  return out;
}

std::int64_t fine_steps() {
  const char* v = std::getenv("CRASHLINK_LONG");
  return v && *v == '1' ? 100000 : 20000;
}

}  // namespace

// Bar (translations) and shell plate (rotations and moments on J too).
TEST(LtsNetwork, RatioOneWithoutOverlapIsLayerToTheBit) {
  for (const auto s : {FreeVibrationShape::Bar, FreeVibrationShape::Plate}) {
    const auto m = linear_model(s, 1.0);
    std::vector<std::vector<double>> u, w;
    for (const char* scheme : {"layer", "lts"}) {
      cosim::LayerNetwork net(m, options(m, 1.0, scheme, 0));
      net.initialize();
      net.run({}, 500 * net.plan().base);
      u.push_back(net.global_displacement());
      std::vector<double> omega;
      for (std::size_t k = 0; k < net.size(); ++k) {
        const auto& o = net.solver(k).angular_velocity_mid();
        omega.insert(omega.end(), o.begin(), o.end());
      }
      w.push_back(std::move(omega));
    }
    ASSERT_EQ(u[0].size(), u[1].size());
    ASSERT_EQ(w[0].size(), w[1].size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < u[0].size(); ++i) differ += u[0][i] != u[1][i];
    for (std::size_t i = 0; i < w[0].size(); ++i) differ += w[0][i] != w[1][i];
    EXPECT_EQ(differ, 0u) << studies::shape_key(s);
    double umax = 0.0;
    for (double x : u[0]) umax = std::max(umax, std::abs(x));
    EXPECT_GT(umax, 0.0) << studies::shape_key(s);  // it moved
  }
}

TEST(LtsNetwork, Sweep) {
  // CRASHLINK_LTS_SWEEP=block:1 (shape:overlap) prints the ratios' measures for a shape.
  const char* v = std::getenv("CRASHLINK_LTS_SWEEP");
  if (!v) GTEST_SKIP() << "set CRASHLINK_LTS_SWEEP=bar|block:overlap";
  const std::string arg(v);
  const auto colon = arg.find(':');
  const std::string shape = arg.substr(0, colon);
  const int overlap = colon == std::string::npos ? 1 : std::atoi(arg.c_str() + colon + 1);
  const auto s = shape == "block"   ? FreeVibrationShape::Block
                 : shape == "plate" ? FreeVibrationShape::Plate
                                    : FreeVibrationShape::Bar;
  for (const double r : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 4.7, 8.0, 16.0}) {
    const LtsRun x = run_lts(s, r, fine_steps(), overlap);
    std::printf(
        "%s ov %d r %-4g (planned %.3f): %lld samples, |E/E0 - 1| <= %.2e; KE + IE + HG band "
        "[%+.4f, %+.4f], max first half %+.4f, second half %+.4f\n",
        shape.c_str(), overlap, r, x.ratio, static_cast<long long>(x.samples), x.e_drift, x.phys_lo,
        x.phys_hi, x.phys_early_hi, x.phys_late_hi);
  }
}

// The issue's bound: E within 1e-6 of its first value (measured: <= 5e-10 on the bar, <= 1e-8 on
// the shell plate, <= 3e-9 on the block, at 2 10^4 fine steps), and the physical energy no more
// than 0.5 % above its first value (measured: <= 0.18 %; it dips by up to 11 % on the bar, 6 % on
// the plate and 3 % on the block while the energy sits in the coarse-instant representation's
// blind spot, and comes back).
TEST(LtsNetwork, LinearBarPlateAndBlockConserveTheirEnergyAtEveryRatio) {
  const auto steps = fine_steps();
  for (const auto s :
       {FreeVibrationShape::Bar, FreeVibrationShape::Plate, FreeVibrationShape::Block})
    for (const double r : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 4.7, 8.0, 16.0}) {
      const LtsRun x = run_lts(s, r, steps, 1);
      std::printf(
          "[measured] lts %s r %-4g (planned %.3f): %lld samples, |E/E0 - 1| <= %.2e; "
          "KE + IE + HG band [%+.4f, %+.4f], max first half %+.4f, second half %+.4f\n",
          studies::shape_key(s), r, x.ratio, static_cast<long long>(x.samples), x.e_drift,
          x.phys_lo, x.phys_hi, x.phys_early_hi, x.phys_late_hi);
      EXPECT_GT(x.samples, 100);
      EXPECT_LT(x.e_drift, 1e-6) << studies::shape_key(s) << " r = " << r;
      EXPECT_LT(x.phys_hi, 0.005) << studies::shape_key(s) << " r = " << r;
    }
}

// A checkpoint taken mid-run and restored gives the uninterrupted run's bits, energy included;
// a `layer` run does not take an lts checkpoint.
TEST(LtsNetwork, RestoredRunEndsWithTheUninterruptedRunsBits) {
  const auto m = linear_model(FreeVibrationShape::Bar, 3.0);
  const auto o = options(m, 3.0, "lts", 1);
  cosim::LayerNetwork straight(m, o);
  straight.initialize();
  const coupling::Tick base = straight.plan().base;
  straight.run({}, 400 * base);
  cosim::LayerNetwork paused(m, o);
  paused.initialize();
  ASSERT_FALSE(paused.run({}, 157 * base));
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_lts_checkpoint_" + std::to_string(::getpid()));
  const auto paths = crashlink::testing::save_network(paused, dir);
  cosim::LayerNetwork resumed(m, o);
  resumed.restore(paths);
  resumed.run({}, 400 * base);
  {
    auto lo = options(m, 3.0, "layer", 0);
    // (its cut differs too: the solver or the stepper refuses, a CheckpointError either way)
    cosim::LayerNetwork layer(m, lo);
    EXPECT_THROW(layer.restore(paths), CheckpointError);
  }
  std::filesystem::remove_all(dir);
  const std::size_t differ =
      crashlink::testing::differing(straight.global_displacement(), resumed.global_displacement());
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(straight.lts_energy_J(), resumed.lts_energy_J());
  EXPECT_TRUE(std::isfinite(resumed.lts_energy_J()));
}

// Three domains in a chain, coarse | mid | fine (0.2 / 0.1 / 0.05 m hexes, steps 1 : 2 : 4): the
// mid domain is the fine side of its owner and the owner of the fine domain. The summed shares,
// sampled at the coarse domain's instants, stay conserved as for two domains (a measurement: the
// nested form's conservation is not derived in docs/multirate.md).
TEST(LtsNetwork, ThreeDomainChainConservesTheSummedEnergy) {
  auto m = crashlink::testing::chain3();
  m.controls.end_time_s = 0.12;  // about 2 10^4 fine steps
  m.controls.bulk_viscosity = false;
  for (auto i : crashlink::testing::where(
           m, [](double x, double, double) { return x < 1e-9 || x > 2.0 - 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  std::uint64_t seed = 7;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    const double x = m.nodes.x0[3 * i];
    const double vx = 1e-6 * std::sin(3.0 * x) + 1e-8 * static_cast<double>(seed >> 40) / 1.6e7;
    m.initial_velocities.push_back({{static_cast<std::int32_t>(i)}, {vx, 0.3 * vx, 0.0}});
  }
  const auto o = crashlink::testing::lts_multi();
  cosim::LayerNetwork net(m, o);
  net.initialize();
  const auto& plan = net.plan();
  ASSERT_EQ(plan.step.size(), 3u);
  auto steps = plan.step;
  std::sort(steps.begin(), steps.end());
  EXPECT_GT(steps[2], steps[1]);
  EXPECT_GT(steps[1], steps[0]);
  const auto [samples, drift] = crashlink::testing::run_summed_energy_drift(net);
  std::printf(
      "[measured] lts chain coarse | mid | fine, steps %lld / %lld / %lld ticks: %lld "
      "samples, |E/E0 - 1| <= %.2e\n",
      static_cast<long long>(steps[2]), static_cast<long long>(steps[1]),
      static_cast<long long>(steps[0]), static_cast<long long>(samples), drift);
  EXPECT_GT(samples, 100);
  EXPECT_LT(drift, 1e-6);
}

// Either domain order (the coarse domain listed first or last) and a 2 x 2 cross-section (the hex
// block): the same cut, the same motion to the bit, the same conserved energy.
TEST(LtsNetwork, DomainOrderDoesNotChangeTheRun) {
  std::vector<std::vector<double>> u;
  std::vector<double> energy;
  for (bool coarse_first : {false, true}) {
    auto m = linear_model(FreeVibrationShape::Block, 3.0);
    if (coarse_first) std::swap(m.domains[0], m.domains[1]);
    cosim::LayerNetwork net(m, options(m, 3.0, "lts", 1));
    net.initialize();
    net.run({}, 300 * net.plan().base);
    u.push_back(net.global_displacement());
    energy.push_back(net.lts_energy_J());
  }
  ASSERT_EQ(u[0].size(), u[1].size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < u[0].size(); ++i) differ += u[0][i] != u[1][i];
  EXPECT_EQ(differ, 0u);
  EXPECT_TRUE(std::isfinite(energy[0]));
  EXPECT_EQ(energy[0], energy[1]);
}

/// {name, x0 [m], length [m], divisions} per bar, one domain each (bar_tree).
using BarParts = std::vector<std::tuple<std::string, double, double, int>>;
/// One owner with two fine domains at different steps (5 mm | 30 mm | 10 mm hexes).
static const std::pair<std::string, BarParts> kOwnerOfTwo{
    "fineA | coarse | fineB",
    {{"fineA", 0.0, 0.1, 20}, {"coarse", 0.1, 0.3, 10}, {"fineB", 0.4, 0.2, 20}}};
/// One fine domain with two owners at different steps (40 mm | 5 mm | 30 mm hexes).
static const std::pair<std::string, BarParts> kFineOfTwo{
    "coarseA | fine | coarseB",
    {{"coarseA", 0.0, 0.2, 5}, {"fine", 0.2, 0.1, 20}, {"coarseB", 0.3, 0.3, 10}}};

/// Steel bars of hexes end to end along x, one domain each ({name, x0 [m], length [m], divisions}),
/// 100 x 100 mm, 2 x 2 elements across (50 mm: the 5-40 mm lengths set the steps), both ends
/// (x = 0 and the last bar's end) held, no load: linear free vibration from a smooth axial and
/// lateral velocity (1e-6 m/s scale).
static model::Model bar_tree(const BarParts& parts) {
  std::string y = R"(name: tree
controls: {end_time: 0.02, bulk_viscosity: {enabled: false}}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
)";
  std::string domains = "domains:\n";
  double total = 0.0;  // [m] where the bars end
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& [name, x0, length, divisions] = parts[i];
    total = x0 + length;
    y += "  " + name + ":\n    material: steel\n" + (i > 0 ? "    merge_nodes: true\n" : "") +
         "    mesh: {generator: bar, origin: [" + std::to_string(x0) +
         ", 0.0, 0.0], axis: x, length: " + std::to_string(length) +
         ", cross_section: [0.1, 0.1], cross_divisions: [2, 2], divisions: " +
         std::to_string(divisions) + "}\n";
    domains += "  " + name + ": {parts: [" + name + "]}\n";
  }
  y += R"(node_sets:
  ends: {box: {min: [-1.0, -1.0, -1.0], max: [1.0e-4, 1.0, 1.0]}}
  far: {box: {min: [)" +
       std::to_string(total - 1e-4) + R"(, -1.0, -1.0], max: [9.0, 1.0, 1.0]}}
boundary:
  - {nodes: ends, fix: all}
  - {nodes: far, fix: all}
)" + domains;
  auto m = io::parse_scenario(y, "tree.yaml");
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double x = m.nodes.x0[3 * i];
    m.initial_velocities.push_back({{static_cast<std::int32_t>(i)},
                                    {1e-6 * std::sin(5.0 * x), 2e-7 * std::sin(9.0 * x), 0.0}});
  }
  return m;
}

// Trees other than a chain, in process, 0.6 m of bars held at both ends: one owner with two fine
// domains at different steps (fineA | coarse | fineB), and one fine domain with two owners at
// different steps (coarseA | fine | coarseB: it takes its rim's plastic returns, and its energy
// samples, at the instants common to both). The summed shares stay conserved as for two domains.
TEST(LtsNetwork, TreesConserveTheSummedEnergy) {
  const std::vector<std::pair<std::string, BarParts>> trees{kOwnerOfTwo, kFineOfTwo};
  for (const auto& [label, parts] : trees) {
    const auto m = bar_tree(parts);
    const auto o = crashlink::testing::lts_multi();
    cosim::LayerNetwork net(m, o);
    net.initialize();
    const auto& plan = net.plan();
    ASSERT_EQ(plan.step.size(), 3u);
    EXPECT_NE(plan.step[0], plan.step[2]) << label << ": both outer domains at one step";
    const auto [samples, drift] = crashlink::testing::run_summed_energy_drift(net);
    std::printf(
        "[measured] lts tree %s, steps %lld / %lld / %lld ticks: %lld samples, |E/E0 - 1| <= "
        "%.2e\n",
        label.c_str(), static_cast<long long>(plan.step[0]), static_cast<long long>(plan.step[1]),
        static_cast<long long>(plan.step[2]), static_cast<long long>(samples), drift);
    EXPECT_GT(samples, 100) << label;
    EXPECT_LT(drift, 1e-6) << label;
  }
}

// A pause of a chain (coarse | mid | fine, steps 4 : 2 : 1) at a coarse instant holds: run(...,
// until) returns with each domain at or just past `until` (a fine side goes on to the substep
// that sends Fbar(T), less than one coarse step here), and a checkpoint taken there and restored
// ends with the straight run's bits and energy. Before the fix every paused domain was nudged on,
// and the chain ran to its end.
TEST(LtsNetwork, ThreeDomainChainPausesAndRestoresToTheBit) {
  auto m = crashlink::testing::chain3();
  m.controls.end_time_s = 0.12;  // far past the instants run to
  m.controls.bulk_viscosity = false;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double x = m.nodes.x0[3 * i];
    m.initial_velocities.push_back(
        {{static_cast<std::int32_t>(i)}, {1e-6 * std::sin(3.0 * x), 0.0, 0.0}});
  }
  const auto o = crashlink::testing::lts_multi();
  cosim::LayerNetwork straight(m, o);
  straight.initialize();
  const coupling::Tick base = straight.plan().base;
  const coupling::Tick until = 57 * base, end = 200 * base;
  ASSERT_FALSE(straight.run({}, end));
  cosim::LayerNetwork paused(m, o);
  paused.initialize();
  ASSERT_FALSE(paused.run({}, until));
  for (std::size_t k = 0; k < paused.size(); ++k) {
    const coupling::Tick t = paused.stepper(k).time();
    EXPECT_GE(t, until) << paused.solver(k).domain_name();
    EXPECT_LT(t, until + base) << paused.solver(k).domain_name() << " ran past the pause";
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_lts_chain_checkpoint_" + std::to_string(::getpid()));
  const auto paths = crashlink::testing::save_network(paused, dir);
  cosim::LayerNetwork resumed(m, o);
  resumed.restore(paths);
  ASSERT_FALSE(resumed.run({}, end));
  std::filesystem::remove_all(dir);
  const std::size_t differ =
      crashlink::testing::differing(straight.global_displacement(), resumed.global_displacement());
  EXPECT_EQ(differ, 0u);
  EXPECT_TRUE(std::isfinite(resumed.lts_energy_J()));
  EXPECT_EQ(straight.lts_energy_J(), resumed.lts_energy_J());
}

// Build item 3, plasticity: the free vibration of the bar, the plate cut along a line and the hex
// block at r = 3 (studies/free_vibration.h, no bulk viscosity, no damping), the material J2 steel
// yielding at 200 MPa (hardening to 240 MPa at 10 %) and the velocities x 10 so that it yields
// at once. The total KE + IE + HG (IE holds the dissipated plastic work) summed over the domains
// at the coarse instants never rises above its first value by more than 1e-4 (measured at most
// 4.2e-6; the elastic runs' band reaches +0.18 %): the coupling adds no energy to a dissipating
// system.
TEST(LtsNetwork, PlasticFreeVibrationGainsNoEnergy) {
  for (auto shape :
       {FreeVibrationShape::Bar, FreeVibrationShape::Plate, FreeVibrationShape::Block}) {
    studies::FreeVibrationConfig cfg;
    cfg.damping = {0.0, 1};
    cfg.uniaxial = shape == FreeVibrationShape::Bar;
    auto m = studies::free_vibration_model(shape, 3.0, cfg);
    m.controls.bulk_viscosity = false;
    m.controls.shell_bulk_viscosity = false;
    m.materials[0].kind = materials::MaterialKind::J2Plastic;
    m.materials[0].hardening.eps_p = {0.0, 0.1};
    m.materials[0].hardening.sigma_y_Pa = {2e8, 2.4e8};
    for (auto& iv : m.initial_velocities)
      for (double& x : iv.velocity_m_s) x *= 10.0;
    cosim::LayerNetwork net(m, options(m, 3.0, "lts", 1));
    net.initialize();
    const auto& plan = net.plan();
    const auto h = *std::min_element(plan.step.begin(), plan.step.end());
    double e0 = -1.0, rise = 0.0, low = 0.0, last = 0.0, sum = 0.0;
    std::size_t count = 0;
    net.run(
        [&](std::size_t k) {
          if (net.stepper(k).time() % plan.base != 0) return;
          sum += net.solver(k).energy().total_J();
          if (++count < net.size()) return;
          count = 0;
          if (e0 < 0.0) e0 = sum;
          rise = std::max(rise, sum / e0 - 1.0);
          low = std::min(low, sum / e0 - 1.0);
          last = sum / e0 - 1.0;
          sum = 0.0;
        },
        20000 * h);
    double eps_p = 0.0;  // the largest plastic strain anywhere: it did yield
    for (std::size_t k = 0; k < net.size(); ++k) {
      const auto& s = net.solver(k);
      for (std::size_t p = 0; p < s.model().parts.size(); ++p) {
        const std::size_t ne = s.model().parts[p].element_count();
        std::vector<double> vm(ne), ep(ne);
        s.element_output(p, {vm.data(), ep.data(), nullptr});
        for (const double e : ep) eps_p = std::max(eps_p, e);
      }
    }
    const char* name = shape == FreeVibrationShape::Bar     ? "bar"
                       : shape == FreeVibrationShape::Plate ? "plate"
                                                            : "block";
    std::printf(
        "[measured] lts plastic free vibration, %s at planned H/h %lld: largest eps_p %.3e, "
        "(KE + IE + HG) / E0 - 1 at the coarse instants in [%+.2e, %+.2e], %+.2e at the last\n",
        name, static_cast<long long>(plan.base / h), eps_p, low, rise, last);
    EXPECT_GT(eps_p, 1e-3) << name << ": it did not yield, no test";
    EXPECT_LT(rise, 1e-4) << name;  // 24 x the largest measured (4.2e-6); elastic band +0.18 %
  }
}

// Pauses anywhere, checkpoints and restores, in trees of 3 to 5 domains (a fine domain with two
// owners, an owner with two fine domains, chains of 3 and 4, a fan of 5), under lts, layer and
// layer with variable steps (where they allow the tree): the run paused every 3.71 coarse
// instants (not on them), restored from a checkpoint at every third pause, ends with the straight
// run's bits (and E under lts). A pause leaves the domains at different instants: the checkpoint
// keeps the messages received and not used yet, and a restored owner's repeats of what its fine
// side had used are dropped (LayerStepper::deliver). Before, the fine domain with two owners
// failed on such a repeat, and then on the force its owner had received and lost.
TEST(LtsNetwork, TreesPausedAnywhereRestoreToTheBit) {
  const std::vector<std::pair<std::string, BarParts>> trees{
      kFineOfTwo,
      kOwnerOfTwo,
      {"chain of 3", {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}}},
      {"chain of 4",
       {{"f", 0.0, 0.1, 40}, {"m1", 0.1, 0.1, 10}, {"m2", 0.2, 0.2, 10}, {"c", 0.4, 0.2, 5}}},
      {"fan of 5 (fB between two owners)",
       {{"fA", 0.0, 0.1, 30},
        {"c1", 0.1, 0.3, 6},
        {"fB", 0.4, 0.1, 14},
        {"c2", 0.5, 0.4, 7},
        {"fC", 0.9, 0.1, 25}}},
  };
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_lts_tree_pauses_" + std::to_string(::getpid()));
  for (const auto& [label, parts] : trees)
    for (const auto& [scheme, variable] : std::vector<std::pair<std::string, bool>>{
             {"lts", false}, {"layer", false}, {"layer", true}}) {
      // variable steps refuse a domain with two owners
      if (variable && (label.rfind("coarseA", 0) == 0 || label.rfind("fan", 0) == 0)) continue;
      auto m = bar_tree(parts);
      m.controls.end_time_s = 1.5e-3;
      cosim::LayerNetworkOptions o;
      o.run.scheme = scheme;
      o.run.common_step = false;
      o.run.variable_steps = variable;
      o.step_safety = 0.9;
      const std::string what = label + ", " + scheme + (variable ? " variable" : "");
      cosim::LayerNetwork straight(m, o);
      straight.initialize();
      ASSERT_TRUE(straight.run()) << what;
      auto net = std::make_unique<cosim::LayerNetwork>(m, o);
      net->initialize();
      const double base = static_cast<double>(net->plan().base);
      int pauses = 0, restores = 0;
      std::int64_t repeats = 0;  // a partner's repeats dropped after the restores
      const auto count_repeats = [&] {
        for (std::size_t k = 0; k < net->size(); ++k) repeats += net->stepper(k).repeats_dropped();
      };
      try {
        for (double f = 0.37;; f += 3.71) {
          if (net->run({}, static_cast<coupling::Tick>(f * base))) break;
          if (++pauses % 3 != 0) continue;
          const auto paths = crashlink::testing::save_network(*net, dir);
          count_repeats();
          net = std::make_unique<cosim::LayerNetwork>(m, o);
          net->restore(paths);
          ++restores;
        }
      } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": " << e.what();
        continue;
      }
      count_repeats();
      const std::size_t differ =
          crashlink::testing::differing(straight.global_displacement(), net->global_displacement());
      EXPECT_EQ(differ, 0u) << what;
      if (scheme == "lts") {
        EXPECT_EQ(straight.lts_energy_J(), net->lts_energy_J()) << what;
      }
      EXPECT_GT(restores, 5) << what;
      std::printf("[measured] %s: %d pauses, %d restores, %lld repeats dropped, %zu dofs differ\n",
                  what.c_str(), pauses, restores, static_cast<long long>(repeats), differ);
      if (label.rfind("coarseA", 0) == 0) {
        EXPECT_GT(repeats, 0) << what << ": no repeat, no test";
      }
    }
  std::filesystem::remove_all(dir);
}
