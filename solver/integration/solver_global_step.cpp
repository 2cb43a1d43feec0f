// The global stable step (Controls::global_stable_step): the assembled mesh's highest frequency
// instead of each element's alone (docs/elements.md "Global stable step").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/cpu_clock.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

namespace {

/// A copy of a part's history with every stress, hourglass force, viscous pressure and damping
/// coefficient zero: the kernels' response to a small rate on it is the elastic stiffness at
/// the current configuration (the material's moduli, no plastic flow: crash codes size the step
/// on the elastic wave speed too).
void zero_history(GlobalStep::State& probe, const GlobalStep::State& run) {
  const auto zero = [](std::vector<double>& a) { std::fill(a.begin(), a.end(), 0.0); };
  if (auto* h = std::get_if<elements::Hex8State>(&probe)) {
    zero(h->stress);
    zero(h->eps_p);
    zero(h->hourglass_force);
    zero(h->bulk_q_Pa);
    zero(h->damping_beta_s);
    zero(h->damping_stress_Pa);
  } else if (auto* s = std::get_if<elements::ShellState>(&probe)) {
    zero(s->sigma_Pa);
    zero(s->eps_p);
    zero(s->resultant_Pa);
    zero(s->shear_Pa);
    zero(s->bulk_q_Pa);
    zero(s->hourglass);
    zero(s->damping_beta_s);
    zero(s->damping_stress_Pa);
    s->thickness_m = std::get<elements::ShellState>(run).thickness_m;  // same size: no allocation
  }
}

}  // namespace

void Solver::set_up_global_step() {
  global_ = GlobalStep{};
  if (!model_.controls.global_stable_step) return;
  auto& g = global_;
  g.on = true;
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    g.probe_states.push_back(parts_[p].state);  // after the initial call: reference recorded
    if (auto* h = std::get_if<elements::Hex8State>(&g.probe_states.back()))
      h->reference_recorded = true;
    if (auto* s = std::get_if<elements::ShellState>(&g.probe_states.back()))
      s->damping_recorded = true;
    const std::size_t ne = std::holds_alternative<std::monostate>(parts_[p].state)
                               ? 0
                               : model_.parts[p].element_count();
    g.probe_dt.emplace_back(ne, 0.0);
    g.ref_inv.emplace_back(ne, 0.0);
  }
  g.inv_sqrt_mass.assign(6 * n_, 0.0);
  g.v.assign(3 * n_, 0.0);
  g.w.assign(3 * n_, 0.0);
  g.f.assign(3 * n_, 0.0);
  g.m.assign(3 * n_, 0.0);
  g.chunk_ratio.assign(std::max(chunks_.chunks(0).size(), chunks_.chunks(1).size()), 1.0);
  g.chunk_element.assign(g.chunk_ratio.size(), -1);
  g.lanczos.reset(6 * n_, GlobalStep::kSteps);
  refresh_global_step(GlobalStep::kInitialRuns);
  for (auto& t : kernel_worker_cpu_) t[2] = 0.0;  // kernel_cost(): the refreshes after set-up
  g.binds = false;
  const double dt = g.dt_global_s * std::min(1.0, g.ratio);
  if (std::isfinite(dt) && dt > dt_stable_) {
    dt_stable_ = dt;
    g.binds = true;
  }
}

void Solver::global_product(const double* z, double* out) {
  auto& g = global_;
  const double* isq = g.inv_sqrt_mass.data();
  const std::size_t n3 = 3 * n_;
  on_node_ranges([&](std::size_t i0, std::size_t i1) {
    for (std::size_t k = 3 * i0; k < 3 * i1; ++k) {
      g.v[k] = z[k] * isq[k];
      g.w[k] = z[n3 + k] * isq[n3 + k];
      g.f[k] = 0.0;
      g.m[k] = 0.0;
    }
  });
  for (std::size_t p = 0; p < parts_.size(); ++p) zero_history(g.probe_states[p], parts_[p].state);
  for (int s = 0; s < 2; ++s) run_span(s, g.probe_dt_s, true, g.f.data(), g.m.data());
  const double inv_dt = 1.0 / g.probe_dt_s;
  on_node_ranges([&](std::size_t i0, std::size_t i1) {
    for (std::size_t k = 3 * i0; k < 3 * i1; ++k) {
      out[k] = g.f[k] * inv_dt * isq[k];
      out[n3 + k] = g.m[k] * inv_dt * isq[n3 + k];
    }
  });
  ++g.products;
}

// The central-difference scheme [2] is stable for dt <= 2 / omega_max, omega_max^2 the largest
// eigenvalue of M^-1 K (Belytschko, Liu, Moran 2000, §6.3.1); element-by-element estimates bound
// omega_max from above by max_e omega_e (Irons' theorem, ibid. §6.3.3) and so give away what the
// assembly's shared nodal masses allow: 0.40-0.98 of 2/omega_max on shell patches and 0.38-0.79 on
// hexahedra (docs/elements.md "Stable step survey"). Abaqus/Explicit's "global estimator" takes
// omega_max of the whole mesh instead; so does this, by the Lanczos process on the symmetric
// A = M^-1/2 K M^-1/2 (held, prescribed and rigid dofs removed), each product A z one kernel
// pass on zero-stress histories with the rates M^-1/2 z over a tiny step (global_product). M
// is the domain's own lumped mass, without the coupling's summed masses, and its ghost nodes
// take part with it: each domain of a cut model is then a sub-assembly, whose omega_max bounds
// the whole mesh's share there from above (Irons' argument). The largest Ritz value theta is
// <= omega_max^2; theta + r (r the residual of its Ritz vector) is the estimate, an upper bound
// only once theta has converged to the top, which the survey's patches show (docs/elements.md
// "Global stable step") and kSafety covers beyond.
// Between refreshes the mesh moves: dt_global is scaled by min_e dt_e(now) / dt_e(refresh)
// (element_ratio), a heuristic (an element's own omega_e bounds its stiffness's growth only up
// to a rotation of its stiff directions) that also carries what the element estimate gives
// away to bulk viscosity and damping, which the elastic probe leaves out. A warm refresh (one
// run from the last Ritz vector) may lower the step but not raise it above the last one so
// scaled; every kFullEvery-th refresh is a full estimate from the pseudo-random vector, which
// may. Runs of kSteps restarted from each other keep the basis at kSteps + 1 vectors.
void Solver::refresh_global_step(int runs) {
  auto& g = global_;
  const bool cold = g.refreshes % GlobalStep::kFullEvery == 0;  // the first one too
  if (cold && g.refreshes > 0) runs = GlobalStep::kFullRuns;
  const double step_now = g.dt_global_s * std::min(1.0, g.ratio);  // what the last one gives now
  // Free dofs and the domain's own lumped masses (assemble_masses without the coupling's
  // overrides; g.f and g.m as scratch before the products), every time: a spot weld's release or
  // a new prescribed motion changes which dofs are free.
  const std::size_t n3 = 3 * n_;
  std::fill(g.f.begin(), g.f.end(), 0.0);
  std::fill(g.m.begin(), g.m.end(), 0.0);
  for (const auto& p : model_.parts) {
    const auto& mat = model_.materials[static_cast<std::size_t>(p.material)];
    if (p.kind == model::ElementKind::Hex8)
      elements::hex8_lumped_mass(p, mat, model_.nodes.x0.data(), g.f.data());
    else
      elements::shell_lumped_mass(p, mat, model_.nodes.x0.data(), g.f.data(), g.m.data());
  }
  for (std::size_t i = 0; i < n_; ++i) {
    const std::uint8_t held = model_.fixed.empty() ? 0 : model_.fixed[i];
    const bool rigid = rigid_node_[i] != 0;
    const double im = !rigid && g.f[i] > 0.0 ? std::sqrt(1.0 / g.f[i]) : 0.0;
    const double ii = !rigid && g.m[i] > 0.0 ? std::sqrt(1.0 / g.m[i]) : 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      g.inv_sqrt_mass[3 * i + d] = (held & (1u << d)) ? 0.0 : im;
      g.inv_sqrt_mass[n3 + 3 * i + d] = (held & (8u << d)) ? 0.0 : ii;
    }
  }
  for (const auto& pd : prescribed_) g.inv_sqrt_mass[(pd.rotational ? n3 : 0) + pd.index] = 0.0;
  double least = std::numeric_limits<double>::infinity();
  for (const auto& rt : parts_) least = std::min(least, rt.last.dt_stable_s);
  if (!std::isfinite(least) || !(least > 0.0)) {  // only rigid parts: nothing to estimate
    g.dt_global_s = std::numeric_limits<double>::infinity();
    g.refresh_cycle = cycle_;
    return;
  }
  g.probe_dt_s = GlobalStep::kProbeStep * least;
  if (cold) g.lanczos.forget();
  for (int r = 0; r < runs; ++r)
    g.last = g.lanczos.run(GlobalStep::kSteps,
                           [&](const double* z, double* out) { global_product(z, out); });
  const double w2 = g.last.theta + g.last.residual;
  double fresh = w2 > 0.0 ? GlobalStep::kSafety * 2.0 / std::sqrt(w2)
                          : std::numeric_limits<double>::infinity();
  // The element steps the estimate goes with (the last product's: the same configuration).
  for (std::size_t p = 0; p < parts_.size(); ++p)
    for (std::size_t e = 0; e < g.ref_inv[p].size(); ++e)
      g.ref_inv[p][e] = g.probe_dt[p][e] > 0.0 ? 1.0 / g.probe_dt[p][e] : 0.0;
  g.ratio = std::numeric_limits<double>::infinity();
  g.ratio_element = -1;
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    if (parts_[p].element_dt_s.size() != g.ref_inv[p].size()) continue;
    std::int64_t where = -1;
    const double r = element_ratio(p, 0, g.ref_inv[p].size(), where);
    if (r < g.ratio) {
      g.ratio = r;
      g.ratio_part = p;
      g.ratio_element = where;
    }
  }
  // A warm estimate never raises the step above what the last one gives now (the new ratio, to
  // the new reference steps, carries bulk viscosity and damping alone).
  if (!cold) fresh = std::min(fresh, step_now / std::min(1.0, g.ratio));
  // A change within kHysteresis is not taken: each change of step in a vibrating mesh moves its
  // energy a little (measured: 1.3 % over 1e5 steps of a patch when every estimate was taken),
  // and the factor kSafety leaves room for it.
  constexpr double kHysteresis = 0.01;
  if (!(std::abs(fresh / g.dt_global_s - 1.0) <= kHysteresis)) g.dt_global_s = fresh;
  g.ratio_at_refresh = g.ratio;
  g.refresh_cycle = cycle_;
  ++g.refreshes;
}

double Solver::element_ratio(std::size_t p, std::size_t first, std::size_t end,
                             std::int64_t& where) const {
  const auto& dt = parts_[p].element_dt_s;
  const auto& inv = global_.ref_inv[p];
  end = std::min(end, inv.size());
  double least = std::numeric_limits<double>::infinity();
  where = -1;
  for (std::size_t e = first; e < end; ++e) {
    const double r = dt[e] * inv[e];
    if (r < least) {
      least = r;
      where = static_cast<std::int64_t>(e);
    }
  }
  return least;
}

void Solver::apply_global_step() {
  auto& g = global_;
  if (!g.on) return;
  if (cycle_ - g.refresh_cycle >= GlobalStep::kRefreshCycles ||
      g.ratio < GlobalStep::kRefreshDrop * g.ratio_at_refresh) {
    const double c0 = core::thread_cpu_seconds();
    refresh_global_step(1);
    global_step_cpu_s_ += core::thread_cpu_seconds() - c0;
  }
  g.binds = false;
  const double dt = g.dt_global_s * std::min(1.0, g.ratio);
  if (std::isfinite(dt) && dt > dt_stable_) {
    dt_stable_ = dt;
    g.binds = true;
  }
}

}  // namespace crashlink::integration
