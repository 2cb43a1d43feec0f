#pragma once
// Variable steps in process (LayerNetwork, LayerSteps::Variable) against mono at its own steps:
// the study's Hann-pulse bar and the interface history, for `layer` and `lts`
// (layer_variable_steps_test.cpp, lts_variable_steps_test.cpp), and the study's free vibration
// without damping (lts_variable_steps_test.cpp, coupled_step_hold_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "studies/free_vibration.h"
#include "tests/unit/partition/partition_models.h"

namespace crashlink::testing {

/// The coupling study's free vibration (studies/free_vibration.h) at mesh ratio 3, domains "fine"
/// and "coarse", without interface damping, bulk viscosity (solids and shells) on or off, ending
/// after `fine_steps` of mono's stable step.
inline model::Model undamped_free_vibration(studies::FreeVibrationShape shape, bool bulk,
                                            double fine_steps) {
  studies::FreeVibrationConfig cfg;
  cfg.damping = {0.0, 1};
  auto m = studies::free_vibration_model(shape, 3.0, cfg);
  m.controls.bulk_viscosity = m.controls.shell_bulk_viscosity = bulk;
  model::Model mono = m;
  mono.domains.clear();
  integration::Solver probe(mono, "probe");
  probe.initialize();
  m.controls.end_time_s = fine_steps * probe.dt_s();
  return m;
}

/// The study's 1-D bar as in layer_network_test.cpp: fine [0, 1] m (n_fine elements), coarse
/// [1, 1 + coarse_length] m with elements r times longer, far end fixed, Hann velocity pulse on
/// x = 0, bulk viscosity on. The step ratio comes from the meshes, not from imposed proposals.
inline model::Model hann_bar(double r, int n_fine = 100, double coarse_length = 2.0,
                             double dt_scale = 0.9) {
  model::Model m;
  m.name = "bar";
  auto mat = elastic("steel");
  mat.poisson_ratio = 0.0;
  m.materials.push_back(mat);
  const double dx = 1.0 / n_fine;
  const int nc = static_cast<int>(std::lround(coarse_length / (r * dx)));
  add_box(m, part("fine", 0), {{0.0, 0.0, 0.0}, {1.0, 0.05, 0.05}, {n_fine, 1, 1}});
  add_box(m, part("coarse", 0), {{1.0, 0.0, 0.0}, {nc * r * dx, 0.05, 0.05}, {nc, 1, 1}});
  finish(m);
  const double xe = 1.0 + nc * r * dx;
  for (auto i : where(m, [&](double x, double, double) { return x > xe - 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  m.controls.end_time_s = 5.0 / std::sqrt(mat.youngs_modulus_Pa / mat.density_kg_m3);
  m.controls.bulk_viscosity = true;
  m.controls.dt_scale = dt_scale;
  m.domains = {{"fine", {0}}, {"coarse", {1}}};
  const double c = std::sqrt(mat.youngs_modulus_Pa / mat.density_kg_m3);
  const double tp = 0.2 / c, v0 = 1.0;
  const model::Curve hann = hann_pulse(tp, v0, 10.0);
  m.prescribed_velocities.push_back(
      {"hann", where(m, [](double x, double, double) { return x < 1e-9; }), 0, hann});
  return m;
}

struct History {
  std::vector<double> t, u, v;
  /// Linear interpolation at t (clamped).
  std::pair<double, double> at(double ts) const {
    const auto it = std::lower_bound(t.begin(), t.end(), ts);
    if (it == t.begin()) return {u.front(), v.front()};
    if (it == t.end()) return {u.back(), v.back()};
    const std::size_t k = static_cast<std::size_t>(it - t.begin());
    const double w = (ts - t[k - 1]) / (t[k] - t[k - 1]);
    return {u[k - 1] + w * (u[k] - u[k - 1]), v[k - 1] + w * (v[k] - v[k - 1])};
  }
};

/// Mono at its own (variable) steps: node `gi`'s x displacement and velocity at every instant.
inline History mono_history(const model::Model& m, std::size_t gi) {
  History h;
  integration::Solver s(m, "mono");
  s.initialize();
  for (;;) {
    s.begin_cycle();
    h.t.push_back(s.time_s());
    h.u.push_back(s.displacement()[3 * gi]);
    h.v.push_back(s.node_velocity(gi)[0]);
    if (s.finished()) break;
    s.end_cycle();
  }
  return h;
}

struct VariableRun {
  double disp = 0.0, vel = 0.0;  ///< interface errors against mono (relative to max)
  std::int64_t fine_cycles = 0, coarse_cycles = 0;
  double fine_dt_min = 0.0, coarse_dt_min = 0.0, coarse_dt_max = 0.0;
  std::size_t coarse_steps_distinct = 0;    ///< how many different coarse steps were taken
  std::size_t substep_counts_distinct = 0;  ///< how many different fine cycles per coarse step
  double coupling_work_J = 0.0, external_work_J = 0.0;
};

/// The Hann bar (or any two-domain model "fine" | "coarse" with its interface node at x = 1 m) in
/// `scheme` with variable steps (fixed_safety > 0: fixed steps at that safety) against mono at its
/// own steps.
inline VariableRun variable_vs_mono(const model::Model& m, double fixed_safety = 0.0,
                                    const std::string& scheme = "layer") {
  std::size_t gi = 0;
  for (std::size_t g = 0; g < m.nodes.count(); ++g)
    if (std::abs(m.nodes.x0[3 * g] - 1.0) < 1e-9) gi = g;
  const History mono = mono_history(m, gi);  // mono at its own steps
  cosim::LayerNetworkOptions o;
  o.run.scheme = scheme;
  o.run.variable_steps = fixed_safety == 0.0;
  if (fixed_safety > 0.0) o.step_safety = fixed_safety;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  std::size_t kf = 0;
  for (std::size_t k = 0; k < net.size(); ++k)
    if (net.solver(k).domain_name() == "fine") kf = k;
  const std::size_t kc = 1 - kf;
  const auto& md = net.domains();
  EXPECT_EQ(md.owner_solver[gi], kf);
  VariableRun r;
  double du = 0.0, umax = 0.0, dv = 0.0, vmax = 0.0;
  std::vector<coupling::Tick> coarse_instants;
  std::vector<coupling::Tick> fine_instants;
  auto sample = [&](std::size_t k) {
    const auto& st = net.stepper(k);
    if (k == kc) {
      coarse_instants.push_back(st.time());
      return;
    }
    fine_instants.push_back(st.time());
    const double t = net.seconds(st.time());
    const std::size_t li = md.owner_local[gi];
    const auto [um, vm] = mono.at(t);
    du = std::max(du, std::abs(net.solver(kf).displacement()[3 * li] - um));
    dv = std::max(dv, std::abs(net.solver(kf).node_velocity(li)[0] - vm));
    umax = std::max(umax, std::abs(um));
    vmax = std::max(vmax, std::abs(vm));
  };
  // The run completing is itself a check: a step above a domain's stable step stops it
  // (Solver::impose_step / impose_committed_step), and so does a fine step passing a coarse
  // instant (LayerStepper::ghost_targets_ready).
  EXPECT_TRUE(net.run(sample));
  std::size_t landed = 0;
  for (auto T : coarse_instants)
    landed += std::binary_search(fine_instants.begin(), fine_instants.end(), T) ? 1 : 0;
  EXPECT_EQ(landed, coarse_instants.size());
  r.disp = du / umax;
  r.vel = dv / vmax;
  r.fine_cycles = net.solver(kf).cycle();
  r.coarse_cycles = net.solver(kc).cycle();
  r.fine_dt_min = net.solver(kf).dt_min_s();
  r.coarse_dt_min = net.solver(kc).dt_min_s();
  std::set<coupling::Tick> steps;
  std::set<std::ptrdiff_t> counts;
  for (std::size_t i = 1; i < coarse_instants.size(); ++i) {
    r.coarse_dt_max =
        std::max(r.coarse_dt_max, net.seconds(coarse_instants[i] - coarse_instants[i - 1]));
    steps.insert(coarse_instants[i] - coarse_instants[i - 1]);
    const auto lo =
        std::lower_bound(fine_instants.begin(), fine_instants.end(), coarse_instants[i - 1]);
    const auto hi =
        std::lower_bound(fine_instants.begin(), fine_instants.end(), coarse_instants[i]);
    counts.insert(hi - lo);
  }
  r.coarse_steps_distinct = steps.size();
  r.substep_counts_distinct = counts.size();
  // the bound on the energy lost to the coupling (issue #4: <= 5 %)
  const auto e = net.energy();
  r.coupling_work_J = e.coupling_work_J;
  r.external_work_J = e.external_work_J;
  EXPECT_LT(std::abs(e.coupling_work_J), 0.05 * e.external_work_J);
  return r;
}

/// A run of `m` (several domains) in `scheme` with variable steps against mono at its own steps on
/// node `gi`: max |u - u_mono| / max |u_mono| at the instants of the domain that owns it; every
/// domain must end at the same instant (the `last` flag), at or after the end time.
struct ChainRun {
  double error = 0.0;
  std::string cycles;  ///< " name cycles" per domain
  double coupling_work_J = 0.0, external_work_J = 0.0;
};

inline ChainRun variable_chain_vs_mono(const model::Model& m, const History& mono, std::size_t gi,
                                       const std::string& scheme) {
  cosim::LayerNetworkOptions o;
  o.run.scheme = scheme;
  o.run.variable_steps = true;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  const auto& d = net.domains();
  const std::size_t k_end = d.owner_solver[gi];
  double du = 0.0, umax = 0.0;
  EXPECT_TRUE(net.run([&](std::size_t k) {
    if (k != k_end) return;
    const double u = net.solver(k).displacement()[3 * d.owner_local[gi]];
    const double um = mono.at(net.seconds(net.stepper(k).time())).first;
    du = std::max(du, std::abs(u - um));
    umax = std::max(umax, std::abs(um));
  }));
  ChainRun r;
  r.error = du / umax;
  for (std::size_t k = 0; k < net.size(); ++k)
    r.cycles += " " + net.solver(k).domain_name() + " " + std::to_string(net.solver(k).cycle());
  for (std::size_t k = 1; k < net.size(); ++k)  // the `last` flag: all end together
    EXPECT_EQ(net.stepper(k).time(), net.stepper(0).time()) << net.solver(k).domain_name();
  EXPECT_GE(net.seconds(net.stepper(0).time()), m.controls.end_time_s * (1.0 - 1e-12));
  const auto e = net.energy();
  r.coupling_work_J = e.coupling_work_J;
  r.external_work_J = e.external_work_J;
  return r;
}

}  // namespace crashlink::testing
