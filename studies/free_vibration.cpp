#include "studies/free_vibration.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "solver/cosim/layer_network.h"
#include "solver/cosim/paper_runner.h"
#include "solver/integration/solver.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/node_merging.h"

namespace crashlink::studies {

// The in-process runners these studies drive (solver/cosim/).
using namespace crashlink::cosim;

const char* shape_name(FreeVibrationShape s) {
  return s == FreeVibrationShape::Bar     ? "bar"
         : s == FreeVibrationShape::Plate ? "shell plate"
                                          : "hex block";
}

const char* shape_key(FreeVibrationShape s) {
  return s == FreeVibrationShape::Bar ? "bar" : s == FreeVibrationShape::Plate ? "plate" : "block";
}

namespace {

model::Part make_part(const std::string& name, double thickness_m) {
  model::Part p;
  p.name = name;
  p.material = 0;
  p.thickness_m = thickness_m;
  return p;
}

}  // namespace

model::Model free_vibration_model(FreeVibrationShape s, double r, const FreeVibrationConfig& cfg) {
  model::Model m;
  m.name = "stability";
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
  const double dx = 0.01;  // m
  const int nf = cfg.fine_elements;
  const double lf = nf * dx;
  const int nc = std::max(4, static_cast<int>(std::lround(lf / (r * dx))));
  const double lc = nc * r * dx;
  // Elements across are r dx wide, so the coarse elements' step grows with r (a section of dx
  // would cap every coarse step at the fine one).
  const double a = std::max(1.0, r) * dx;
  if (s == FreeVibrationShape::Plate) {
    model::generate_plate(m, make_part("fine", 0.002),
                          {{0, 0, 0}, {lf, 0, 0}, {0, 3 * a, 0}, {nf, 3}, 0.0});
    const std::size_t first = m.nodes.count();
    model::generate_plate(m, make_part("coarse", 0.002),
                          {{lf, 0, 0}, {lc, 0, 0}, {0, 3 * a, 0}, {nc, 3}, 0.0});
    model::merge_coincident_nodes(m, first, 1e-6);
  } else {
    const int nyz = s == FreeVibrationShape::Bar ? 1 : 2;
    model::generate_box(m, make_part("fine", 0.0),
                        {{0, 0, 0}, {lf, nyz * a, nyz * a}, {nf, nyz, nyz}});
    const std::size_t first = m.nodes.count();
    model::generate_box(m, make_part("coarse", 0.0),
                        {{lf, 0, 0}, {lc, nyz * a, nyz * a}, {nc, nyz, nyz}});
    model::merge_coincident_nodes(m, first, 1e-6);
  }
  const std::size_t n = m.nodes.count();
  m.fixed.assign(n, 0);
  const double xe = lf + lc;
  std::uint64_t seed = 12345;
  auto noise = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
  };
  auto section_noise = [](double x) {  // a hash of the section's position: same x, same value
    std::uint64_t h = static_cast<std::uint64_t>(std::llround(x * 1e6)) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 32;
    return static_cast<double>(h >> 11) / 9007199254740992.0 - 0.5;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double x = m.nodes.x0[3 * i];
    if (x < 1e-9 || x > xe - 1e-9) m.fixed[i] = s == FreeVibrationShape::Plate ? 63 : 7;
    const bool lateral = !(cfg.uniaxial && s != FreeVibrationShape::Plate);
    if (!lateral) m.fixed[i] |= 6;                                  // y, z held
    const double v = (x / lf >= 0.3 && x / lf <= 0.5) ? 1.0 : 0.0;  // m/s
    // uniaxial: one noise value per cross-section (x), so no shear mode is seeded
    const double nx = lateral ? noise() : section_noise(x);
    const double vx = v + 1e-4 * nx, vy = 0.3 * v + 1e-4 * noise(),
                 vz = (s == FreeVibrationShape::Plate ? 0.3 * v : 0.0) + 1e-4 * noise();
    m.initial_velocities.push_back(
        {{static_cast<std::int32_t>(i)}, {vx, lateral ? vy : 0.0, lateral ? vz : 0.0}});
  }
  m.controls.end_time_s = 100.0;
  m.controls.bulk_viscosity = true;
  m.controls.shell_bulk_viscosity = cfg.shell_bulk_viscosity;
  m.controls.bulk_linear_in_expansion = cfg.bulk_linear_in_expansion;
  m.controls.bulk_q_linear = cfg.bulk_q_linear;
  m.domains = {{"fine", {0}}, {"coarse", {1}}};
  m.coupling.interface_damping = cfg.damping;
  return m;
}

FreeVibrationResult run_layer_free_vibration(FreeVibrationShape s, double r,
                                             std::int64_t fine_steps,
                                             const FreeVibrationConfig& cfg,
                                             const FreeVibrationSample& on_sample) {
  return run_layer_energy(free_vibration_model(s, r, cfg), r, fine_steps, on_sample);
}

namespace {

/// The two measures over the samples of the summed energy E at instants t (free_vibration.h):
/// rise above the running minimum, and the same after `t_settle`, both / E0; E_end.
struct EnergyRise {
  FreeVibrationResult& out;
  double t_settle = 0.0;
  double running_min = 0.0, late_min = 0.0;
  bool first = true, late = false;
  void add(double t, double sum) {
    if (first) {
      out.e0_J = running_min = sum;
      first = false;
    }
    running_min = std::min(running_min, sum);
    if ((sum - running_min) / out.e0_J > out.rise) {
      out.rise = (sum - running_min) / out.e0_J;
      out.t_rise_s = t;
    }
    if (t >= t_settle) {
      late_min = late ? std::min(late_min, sum) : sum;
      late = true;
      out.late_rise = std::max(out.late_rise, (sum - late_min) / out.e0_J);
    }
    out.e_end_J = sum;
  }
  double since_min(double sum) const { return (sum - running_min) / out.e0_J; }
};

}  // namespace

LayerNetworkOptions free_vibration_options(const model::Model& m, double r,
                                           const std::string& scheme, double fine_factor,
                                           double step_safety, int overlap_layers) {
  double h0 = 0.0;
  {
    model::Model mono = m;
    mono.domains.clear();
    integration::Solver probe(mono, "probe");
    probe.initialize();
    h0 = fine_factor * probe.dt_s();
  }
  LayerNetworkOptions o;
  o.run.scheme = scheme;
  o.overlap_layers = overlap_layers;
  {
    LayerNetwork shape_probe(m, o);
    const auto& d = shape_probe.domains();
    o.proposal_s.assign(d.solvers.size(), 0.0);
    for (std::size_t k = 0; k < d.solvers.size(); ++k)
      o.proposal_s[k] = d.solvers[k]->domain_name() == "fine" ? h0 : r * h0;
  }
  o.step_safety = step_safety;
  return o;
}

namespace {

/// run_layer_energy; throws what stops the set-up (a run stopped midway is caught inside).
/// `scheme`: "layer" or "lts" (LayerForm).
FreeVibrationResult layer_energy(const model::Model& m, double r, std::int64_t fine_steps,
                                 const FreeVibrationSample& on_sample,
                                 const std::string& scheme = "layer") {
  LayerNetwork net(m, free_vibration_options(m, r, scheme));
  net.initialize();
  const auto& plan = net.plan();
  const auto h_min = *std::min_element(plan.step.begin(), plan.step.end());
  const auto h_max = *std::max_element(plan.step.begin(), plan.step.end());
  FreeVibrationResult out;
  out.ratio = static_cast<double>(h_max) / static_cast<double>(h_min);
  const coupling::Tick t_end = fine_steps * h_min, t_settle = t_end / 5;
  out.simulated_s = net.seconds(t_end);
  double sum = 0.0, hourglass = 0.0;
  std::vector<double> work(net.size(), 0.0);
  std::size_t count = 0;
  EnergyRise measure{out, net.seconds(t_settle)};
  try {
    net.run(
        [&](std::size_t k) {
          const coupling::Tick t = net.stepper(k).time();
          if (t % plan.base != 0) return;
          const auto& e = net.solver(k).energy();
          sum += e.total_J();
          hourglass += e.hourglass_J;
          work[k] = e.coupling_work_J;
          if (++count < net.size()) return;
          measure.add(net.seconds(t), sum);
          if (on_sample) {
            std::vector<double> w(work);
            for (double& x : w) x /= out.e0_J;
            on_sample(net.seconds(t), sum / out.e0_J - 1.0, measure.since_min(sum),
                      hourglass / out.e0_J, w);
          }
          sum = hourglass = 0.0;
          count = 0;
        },
        t_end);
  } catch (const Error& e) {
    out.error = e.what();
  }
  coupling::Tick reached = 0;
  for (std::size_t k = 0; k < net.size(); ++k)
    reached = k == 0 ? net.stepper(k).time() : std::min(reached, net.stepper(k).time());
  out.fine_steps_run = reached / h_min;
  return out;
}

}  // namespace

FreeVibrationResult run_layer_energy(const model::Model& m, double r, std::int64_t fine_steps,
                                     const FreeVibrationSample& on_sample) {
  try {
    return layer_energy(m, r, fine_steps, on_sample);
  } catch (const Error& e) {  // the cut or the plan refused: nothing ran
    FreeVibrationResult out;
    out.error = e.what();
    return out;
  }
}

FreeVibrationResult run_lts_free_vibration(FreeVibrationShape s, double r, std::int64_t fine_steps,
                                           const FreeVibrationConfig& cfg) {
  FreeVibrationConfig c = cfg;
  c.damping = {0.0, 1};  // lts has no interface damping (the cut refuses it)
  try {
    return layer_energy(free_vibration_model(s, r, c), r, fine_steps, {}, "lts");
  } catch (const Error& e) {  // the cut or the plan refused: nothing ran
    FreeVibrationResult out;
    out.error = e.what();
    return out;
  }
}

FreeVibrationResult run_paper_free_vibration(FreeVibrationShape s, double r,
                                             std::int64_t fine_steps,
                                             const FreeVibrationConfig& cfg, bool drift) {
  FreeVibrationConfig c = cfg;
  c.damping = {0.0, 1};  // the paper has no interface damping (a `layer` stabiliser)
  return run_paper_energy(free_vibration_model(s, r, c), r, fine_steps, drift);
}

FreeVibrationResult run_paper_energy(const model::Model& m, double r, std::int64_t fine_steps,
                                     bool drift) {
  FreeVibrationResult out;
  try {
    PaperOptions o;
    // H/h = r rounded down to a whole number (the scheme needs one), h under 0.9 of both domains'
    // own stable steps (C's divided by the ratio).
    o.ratio_p = std::max(1, static_cast<int>(std::floor(r + 1e-9)));
    o.step_safety = 0.9;
    o.run.drift = drift;
    PaperRunner runner(m, o);
    runner.initialize();
    struct Count {  // the fine steps done, also when advance() throws
      FreeVibrationResult& out;
      const PaperRunner& r;
      ~Count() { out.fine_steps_run = r.fine_steps(); }
    } count{out, runner};
    out.ratio = static_cast<double>(runner.ratio());
    out.simulated_s = runner.fine_dt_s() * static_cast<double>(fine_steps);
    EnergyRise measure{out, 0.2 * out.simulated_s};
    while (runner.fine_steps() < fine_steps) {
      runner.advance();
      measure.add(runner.seconds(runner.coarse_time_ticks()), runner.energy().total_J());
    }
  } catch (const Error& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace crashlink::studies
