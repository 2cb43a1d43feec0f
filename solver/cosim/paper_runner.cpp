// PaperRunner: the `paper` scheme ([5]-[11] of Bourel 2005) for two domains in one process
// (paper_runner.h; docs/design.md §2.2-§2.5, §2.7; scheme S1 of coupling-study/mts.py).
#include "solver/cosim/paper_runner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "core/errors.h"
#include "coupling/interpolation.h"
#include "solver/cosim/paper_nodes.h"

namespace crashlink::cosim {

namespace paper = coupling::paper;

namespace {

double norm3(const double* a, const double* b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

PaperRunner::PaperRunner(const model::Model& global, PaperOptions options)
    : global_(global),
      options_(options),
      dec_(partition::decompose(global, partition::Scheme::Paper)) {
  std::vector<int> used;
  for (std::size_t d = 0; d < dec_.domains.size(); ++d)
    if (!dec_.domains[d].empty()) used.push_back(static_cast<int>(d));
  if (used.size() != 2)
    throw ModelError("paper: the paper cut gives " + std::to_string(used.size()) +
                     " non-empty domains; this runner couples exactly two (fine and coarse)");
  if (dec_.interfaces.empty())
    throw ModelError(
        "paper: the two domains share no node and no contact; nothing to couple (run them as two "
        "separate models)");
  domain_[0] = dec_.interfaces.front().fine;
  domain_[1] = dec_.interfaces.front().coarse;
  for (const auto& itf : dec_.interfaces)
    if (itf.fine != domain_[0] || itf.coarse != domain_[1])
      throw ModelError("paper: the interfaces disagree on which domain is the fine one");
  if (options_.run.ticks_per_second < 1) throw ModelError("paper: ticks_per_second must be >= 1");
  if (options_.run.scheme != "paper" || options_.run.variable_steps)
    throw ModelError("paper: this runner runs `paper` at fixed steps (run.scheme '" +
                     options_.run.scheme + "', run.variable_steps " +
                     (options_.run.variable_steps ? "true" : "false") +
                     "); variable steps run over processes (crashlink run --coupling paper "
                     "--variable-steps)");

  const std::size_t ng = global.nodes.count();
  std::vector<double> partial_mass[2], partial_inertia[2];  // (the inertia: scratch)
  for (int s = 0; s < 2; ++s) {
    const auto& dm = dec_.domains[static_cast<std::size_t>(domain_[s])];
    g2l_[s].assign(ng, kAbsent);
    for (std::size_t l = 0; l < dm.global_node.size(); ++l)
      g2l_[s][static_cast<std::size_t>(dm.global_node[l])] = l;
    partial_masses(dm.model, partial_mass[s], partial_inertia[s]);
  }

  // The coupled nodes, every link node and every copy once, in the order both domains list them
  // (cosim::paper_nodes: every interface involves both here, so the two lists pair up).
  const auto fine_nodes = paper_nodes(dec_, domain_[0]);
  const auto coarse_nodes = paper_nodes(dec_, domain_[1]);
  if (fine_nodes.size() != coarse_nodes.size())
    throw ModelError("paper: the two domains list " + std::to_string(fine_nodes.size()) + " and " +
                     std::to_string(coarse_nodes.size()) +
                     " coupled nodes (internal error of the cut)");
  refuse_rotations_on_both_sides(dec_, domain_[0], fine_nodes);
  for (std::size_t j = 0; j < fine_nodes.size(); ++j) {
    const auto& f = fine_nodes[j];
    const auto& c = coarse_nodes[j];
    CRASHLINK_ASSERT(f.global == c.global);
    PaperNode pn;
    pn.global = f.global;
    pn.local[0] = f.local;
    pn.local[1] = c.local;
    pn.reference = f.reference ? 0 : 1;
    pn.copy = f.copy || c.copy;
    nodes_.push_back(pn);
  }

  // [5]: M = sum_k m^k over the two presences (a copy contributes 0), in side order.
  const std::size_t n = nodes_.size();
  std::vector<double> partial[2];
  for (int s = 0; s < 2; ++s) {
    partial[s].resize(n);
    for (std::size_t j = 0; j < n; ++j) partial[s][j] = partial_mass[s][nodes_[j].local[s]];
  }
  const std::vector<double> M = paper::summed_mass(partial);
  for (std::size_t j = 0; j < n; ++j) {
    nodes_[j].mass_kg = M[j];
    // The cut's own sum (the natural mass over the global model) must agree: a node shared by a
    // third domain, or a copy of a node of a third domain, would not.
    for (int s = 0; s < 2; ++s) {
      const double mk =
          dec_.domains[static_cast<std::size_t>(domain_[s])].interface_mass_kg[nodes_[j].local[s]];
      if (std::abs(mk - M[j]) > 1e-12 * M[j])
        throw ModelError("paper: node id " + std::to_string(global.nodes.id[nodes_[j].global]) +
                         ": summed mass " + std::to_string(M[j]) +
                         " kg of the two domains differs "
                         "from its natural mass " +
                         std::to_string(mk) + " kg (is it used by a third domain?)");
    }
  }
  for (int s = 0; s < 2; ++s) {
    const auto& dm = dec_.domains[static_cast<std::size_t>(domain_[s])];
    solvers_[s] = std::make_unique<integration::Solver>(dm.model, dm.name);
    std::vector<double> override(dm.global_node.size(), 0.0);
    for (const auto& pn : nodes_) {
      override[pn.local[s]] = pn.mass_kg;
      if (pn.reference == s) reference_nodes_[s].push_back(pn.local[s]);
    }
    solvers_[s]->set_mass_override(std::move(override));
  }
  for (auto* v :
       {&a_free_[0], &a_free_[1], &u_[0], &u_[1], &aC_lo_, &aC_hi_, &uC_lo_, &uC_hi_, &a_link_,
        &u_ref_, &da_, &a_star_, &u_last_[0], &u_last_[1], &fd_last_[0], &fd_last_[1]})
    v->assign(3 * n, 0.0);
}

coupling::Tick PaperRunner::to_ticks(double t_s) const {
  // coupling::TickClock::to_ticks' rule (round down, snap within 4 ulps of a whole tick).
  if (!std::isfinite(t_s) || !(t_s > 0.0))
    throw NumericalError("paper: step " + std::to_string(t_s) + " s is not positive");
  const double x = t_s * static_cast<double>(options_.run.ticks_per_second);
  const double nearest = std::nearbyint(x);
  const double snap = 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, x);
  const double k = std::abs(x - nearest) <= snap ? nearest : std::floor(x);
  if (k < 1.0 || k > 4.6e18)
    throw ModelError("paper: step " + std::to_string(t_s) +
                     " s is not representable in ticks; change ticks_per_second");
  return static_cast<coupling::Tick>(k);
}

void PaperRunner::initialize() {
  auto& F = *solvers_[0];
  auto& C = *solvers_[1];
  F.initialize();
  C.initialize();
  if (options_.ratio_p > 0) {
    if (options_.ratio_q < 1 || !(options_.step_safety > 0.0 && options_.step_safety <= 1.0))
      throw ModelError("paper: ratio_q must be >= 1 and step_safety in (0, 1]");
    const double p = options_.ratio_p, q = options_.ratio_q;
    const coupling::Tick unit =
        to_ticks(options_.step_safety * std::min(F.dt_s(), C.dt_s() * q / p)) / options_.ratio_q;
    if (unit < 1) throw ModelError("paper: the fine step is shorter than ratio_q ticks");
    h_ = unit * options_.ratio_q;
    H_ = unit * options_.ratio_p;
  } else {
    h_ = to_ticks(options_.fine_dt_s > 0.0 ? options_.fine_dt_s : F.dt_s());
    H_ = to_ticks(options_.coarse_dt_s > 0.0 ? options_.coarse_dt_s : C.dt_s());
  }
  if (options_.integer_ratio) H_ = std::max<coupling::Tick>(h_, (H_ / h_) * h_);
  if (H_ < h_)
    throw ModelError("paper: the coarse step (" + std::to_string(seconds(H_)) +
                     " s) is shorter than the fine step (" + std::to_string(seconds(h_)) + " s)");
  if (H_ % h_ != 0)
    throw ModelError("paper: H / h = " + std::to_string(H_) + " / " + std::to_string(h_) +
                     " ticks is not a whole number; this runner needs the fine domain on every "
                     "coarse instant (the coarse side is corrected there with [8] and the fine "
                     "side's exact free state); fix: integer_ratio = true, or a whole ratio_p / "
                     "ratio_q");
  F.impose_step(seconds(h_));
  C.impose_step(seconds(H_));
  tF_ = tC_ = 0;
  fine_steps_ = coarse_steps_ = 0;
  energy_ = integration::EnergyAccount{};
  ke_twice0_ = 0.0;
  guard_ = paper::EnergyGuard(options_.run.guard_rise);
  drift_work_J_ = 0.0;
  gap_ = max_gap_ = PaperGap{};
  for (int s = 0; s < 2; ++s) {
    read_free(s);
    u_last_[s] = u_[s];
    std::fill(fd_last_[s].begin(), fd_last_[s].end(), 0.0);
  }
}

void PaperRunner::read_free(int side) {
  const auto& S = *solvers_[side];
  const auto& a = S.acceleration();
  const auto& u = S.displacement();
  for (std::size_t j = 0; j < nodes_.size(); ++j)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * nodes_[j].local[side] + d;
      a_free_[side][3 * j + d] = a[k];
      u_[side][3 * j + d] = u[k];
    }
}

void PaperRunner::check_finite(const std::vector<double>& a, int side, const char* what) const {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(a[i])) {
      const auto& pn = nodes_[i / 3];
      unstable(fmt::format(
          "the {} acceleration of coupled node {} in domain '{}' is {} (nothing was written)", what,
          global_.nodes.id[pn.global], solvers_[side]->domain_name(), a[i]));
    }
}

void PaperRunner::correct(int side, const std::vector<double>& a_link,
                          const std::vector<double>& u_ref, double step_product) {
  // [11] on the non-reference side (u_ref == own u elsewhere: da = 0 there), a* = a_link + da.
  paper::drift_correction(u_ref, u_[side], step_product, drift(), da_);
  paper::add_drift(a_link, da_, a_star_);
  check_finite(a_star_, side, "corrected");
  auto& S = *solvers_[side];
  const auto& fixed = S.model().fixed;
  for (std::size_t j = 0; j < nodes_.size(); ++j) {
    const auto& pn = nodes_[j];
    Vec3 a{};
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * j + d;
      // Work of the drift force M da by the Solver's trapezoid rule: F^n weighs
      // (u^{n+1} - u^{n-1}) / 2, accumulated as the two halves around t^n.
      const double fd = pn.mass_kg * da_[k];
      drift_work_J_ += 0.5 * (fd_last_[side][k] + fd) * (u_[side][k] - u_last_[side][k]);
      fd_last_[side][k] = fd;
      u_last_[side][k] = u_[side][k];
      const bool is_fixed = !fixed.empty() && (fixed[pn.local[side]] & (1u << d));
      a[d] = is_fixed ? 0.0 : a_star_[k];
    }
    S.set_acceleration(pn.local[side], a);  // counts M (a* - a_free) as coupling work
  }
}

void PaperRunner::sample_energy() {
  // Both domains at T after begin_cycle(): their accounts are complete (solver.h).
  integration::EnergyAccount e;
  for (const auto& s : solvers_) e.add_terms(s->energy());
  // Kinetic energy of the coupled nodes counted twice (M in both domains): drop the REFERENCE
  // side's, in the Solver's product form 1/2 M v^{n-1/2} . v^{n+1/2}. The non-reference presence
  // (fine side of a link, a copy) is the one [11] acts on: keeping its kinetic energy keeps an
  // oscillation of it relative to the reference in the guard's energy.
  const double twice = product_kinetic_energy(*solvers_[0], reference_nodes_[0]) +
                       product_kinetic_energy(*solvers_[1], reference_nodes_[1]);
  if (!guard_.started()) ke_twice0_ = twice;
  e.kinetic_J -= twice;
  e.initial_total_J -= ke_twice0_;
  e.coupling_work_J -= twice - ke_twice0_;  // net work of the corrections
  e.reference_J = energy_.reference_J;
  e.update_reference();
  energy_ = e;

  // Guard: the energy not explained by the loads = initial energy + net coupling work.
  if (auto why = guard_.sample(e.total_J() - e.external_work_J, e.total_J(),
                               e.initial_total_J + e.external_work_J))
    unstable(
        fmt::format("{}; net work of the link and drift corrections {:.4e} J, of which "
                    "drift [11] {:.4e} J",
                    *why, e.coupling_work_J, drift_work_J_));
}

void PaperRunner::unstable(const std::string& what) const {
  throw NumericalError(paper::unstable_message(
      fmt::format("at t = {:.6e} s (coarse step {}, fine step {})", seconds(std::max(tF_, tC_)),
                  coarse_steps_, fine_steps_),
      what, drift(),
      fmt::format("H/h = {} (h = {:.4e} s, H = {:.4e} s)", ratio(), fine_dt_s(), coarse_dt_s())));
}

void PaperRunner::advance(const std::function<void()>& on_fine) {
  auto& F = *solvers_[0];
  auto& C = *solvers_[1];
  const std::size_t n = nodes_.size();
  const std::int64_t r = ratio();
  // Entry: both at T with their free states ([5]).
  read_free(0);
  read_free(1);
  check_finite(a_free_[0], 0, "free");
  check_finite(a_free_[1], 1, "free");
  gap_ = PaperGap{};
  for (std::size_t j = 0; j < n; ++j) {
    const double g = norm3(&u_[0][3 * j], &u_[1][3 * j]);
    double& slot = nodes_[j].copy ? gap_.copy_m : gap_.link_m;
    slot = std::max(slot, g);
  }
  max_gap_.link_m = std::max(max_gap_.link_m, gap_.link_m);
  max_gap_.copy_m = std::max(max_gap_.copy_m, gap_.copy_m);
  aC_lo_ = a_free_[1];
  uC_lo_ = u_[1];

  // [8] at T, the same bits for both sides.
  const std::array<std::span<const double>, 2> both{a_free_[0], a_free_[1]};
  paper::link_acceleration(both, a_link_);
  // C at T: [11] where C is the non-reference side (copies of F's slave nodes), u_ref = u_F(T).
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t d = 0; d < 3; ++d)
      u_ref_[3 * j + d] = nodes_[j].reference == 0 ? u_[0][3 * j + d] : u_[1][3 * j + d];
  correct(1, a_link_, u_ref_, paper::drift_step_product(C.dt_s(), C.cycle() == 0 ? 0.0 : C.dt_s()));
  // F at T: [11] where F is the non-reference side, u_ref = u_C(T).
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t d = 0; d < 3; ++d)
      u_ref_[3 * j + d] = nodes_[j].reference == 1 ? u_[1][3 * j + d] : u_[0][3 * j + d];
  correct(0, a_link_, u_ref_, paper::drift_step_product(F.dt_s(), F.cycle() == 0 ? 0.0 : F.dt_s()));

  C.begin_cycle();  // T
  F.begin_cycle();  // T
  sample_energy();
  if (on_fine) on_fine();

  // C to T+H: its free state there ([5]).
  C.end_cycle_forces();
  C.end_cycle_accelerations();
  C.impose_step(seconds(H_));
  read_free(1);
  check_finite(a_free_[1], 1, "free");
  aC_hi_ = a_free_[1];
  uC_hi_ = u_[1];

  // F's fine steps inside [T, T+H]: [9] with [10], and [11] against u_C interpolated by [10].
  const coupling::Tick T = tC_, T1 = tC_ + H_;
  for (std::int64_t k = 1; k <= r; ++k) {
    F.end_cycle_forces();
    F.end_cycle_accelerations();
    F.impose_step(seconds(h_));
    tF_ += h_;
    ++fine_steps_;
    if (k == r) break;  // at T+H: the next advance() corrects it
    read_free(0);
    check_finite(a_free_[0], 0, "free");
    const coupling::Weight w = paper::interpolation_weight(tF_, T, T1);
    paper::multiscale_acceleration(a_free_[0], aC_lo_, aC_hi_, w, a_link_);
    coupling::interpolate(uC_lo_, uC_hi_, w, u_ref_);
    for (std::size_t j = 0; j < n; ++j)
      if (nodes_[j].reference == 0)  // F is the reference here: no drift on F
        for (std::size_t d = 0; d < 3; ++d) u_ref_[3 * j + d] = u_[0][3 * j + d];
    correct(0, a_link_, u_ref_, paper::drift_step_product(F.dt_s(), F.dt_s()));
    F.begin_cycle();
    if (on_fine) on_fine();
  }
  if (tF_ != T1) throw NumericalError("paper: the fine domain missed the coarse instant");
  tC_ = T1;
  ++coarse_steps_;
}

std::vector<double> PaperRunner::global_displacement() const {
  const std::size_t ng = global_.nodes.count();
  std::vector<double> u(3 * ng, 0.0);
  for (int s = 0; s < 2; ++s) {
    const auto& dm = dec_.domains[static_cast<std::size_t>(domain_[s])];
    const auto& us = solvers_[s]->displacement();
    for (std::size_t l = 0; l < dm.global_node.size(); ++l) {
      if (dm.copy[l]) continue;
      const auto g = static_cast<std::size_t>(dm.global_node[l]);
      for (std::size_t d = 0; d < 3; ++d) u[3 * g + d] = us[3 * l + d];
    }
  }
  for (const auto& pn : nodes_) {  // a coupled node from its reference side
    const auto& us = solvers_[pn.reference]->displacement();
    for (std::size_t d = 0; d < 3; ++d) u[3 * pn.global + d] = us[3 * pn.local[pn.reference] + d];
  }
  return u;
}

}  // namespace crashlink::cosim
