// LayerStepper's `lts` form (layer_stepper.h LayerForm; docs/multirate.md "lts"): the reflected
// ghost path and the hat-averaged force of leapfrog local time stepping (Diaz & Grote 2009) in its
// physical-state form, and the conserved energy's samples.
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

#include "core/errors.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

void LayerStepper::set_form(LayerForm form, Tick energy_period) {
  const std::string& dom = solver_.domain_name();
  if (initialized_)
    throw ModelError(fmt::format("layer stepper '{}': set_form() after initialize()", dom));
  if (form == LayerForm::Lts && variable_) {
    // The first owner step is the plan's: every fine port's owner step a whole number of this
    // domain's planned steps. No E (it needs one coarse step): energy_period is not used.
    if (common_)
      throw ModelError(fmt::format(
          "layer stepper '{}': lts runs `multi` steps; `split` (one common step) is `layer`", dom));
    for (const auto& port : ports_)
      if (port.fine_side &&
          (planned_h_ < 1 || port.partner_step < planned_h_ || port.partner_step % planned_h_))
        throw ModelError(fmt::format(
            "layer stepper '{}': lts with variable steps starts from the plan: the owner's step "
            "{} ticks on interface {} is not a whole multiple of this domain's {} ticks",
            dom, port.partner_step, port.index, planned_h_));
  } else if (form == LayerForm::Lts) {
    if (energy_period < h_ || energy_period % h_ != 0)
      throw ModelError(fmt::format(
          "layer stepper '{}': lts energy period {} ticks is not a whole multiple of this "
          "domain's step {} ticks; the period must be the step plan's base (Setup.base_ticks: a "
          "coordinator older than protocol 9 sends 0)",
          dom, energy_period, h_));
    for (std::size_t p = 0; p < ports_.size(); ++p) {
      if (ports_[p].fine_side && energy_period % ports_[p].partner_step != 0)
        throw ModelError(fmt::format(
            "layer stepper '{}': lts energy period {} ticks is not a whole multiple of the "
            "owner's step {} ticks on interface {}; the period must be the step plan's base",
            dom, energy_period, ports_[p].partner_step, ports_[p].index));
    }
  }
  form_ = form;
  energy_period_ = energy_period;
  // The reflected path's velocity is no physical one: the elements on J compute no bulk viscosity.
  if (form == LayerForm::Lts) solver_.set_ghost_bulk_viscosity(false);
}

void LayerStepper::lts_start_port(const LayerPort& port, PortState& ps) const {
  // t = 0: the path of the first owner step starts at u_J(0); no force accumulated yet.
  const std::size_t n3 = 3 * port.local.size();
  ps.substeps = port.partner_step / h_;
  if (variable_) {  // the instants of the rows, the halves of Fbar (layer_stepper_lts_variable)
    ps.path_prev_t.assign(static_cast<std::size_t>(ps.substeps + 1), 0);
    ps.path_cur_t.assign(static_cast<std::size_t>(ps.substeps + 1), 0);
    ps.fbar_left.assign(n3, 0.0);
    ps.g_T.assign(n3, 0.0);
    ps.mbar_left.assign(ps.rotates ? n3 : 0, 0.0);
    ps.m_T.assign(ps.rotates ? n3 : 0, 0.0);
    ps.H_prev = 0;
  }
  const auto rows = static_cast<std::size_t>(ps.substeps + 1);
  ps.path_prev.assign(rows * n3, 0.0);
  ps.path_cur.assign(rows * n3, 0.0);
  std::copy(ps.u_T.begin(), ps.u_T.end(), ps.path_cur.begin());
  ps.fbar_T.assign(n3, 0.0);
  ps.fbar_T1.assign(n3, 0.0);
  ps.acc_T = 0;
  const std::size_t r3 = ps.rotates ? n3 : 0;
  ps.omega_prev.assign(static_cast<std::size_t>(ps.substeps) * r3, 0.0);
  ps.omega_cur.assign(static_cast<std::size_t>(ps.substeps) * r3, 0.0);
  ps.mbar_T.assign(r3, 0.0);
  ps.mbar_T1.assign(r3, 0.0);
}

void LayerStepper::lts_next_owner_step(PortState& ps) const {
  // The owner step just ended becomes the one the next path reflects; the new one starts at
  // u_J(T) (ps.u_T, already moved on).
  ps.path_prev.swap(ps.path_cur);
  std::copy(ps.u_T.begin(), ps.u_T.end(), ps.path_cur.begin());
  ps.omega_prev.swap(ps.omega_cur);
}

void LayerStepper::lts_ghost_targets(const LayerPort& port, PortState& ps, Tick t1) {
  if (variable_) {
    lts_ghost_targets_variable(port, ps, t1);
    return;
  }
  // J at t1 = T + q h: the owner's u_J(T + H) at q = p; else the reflected path
  // U(T + q h) = 2 u_J(T) - U(T - q h) (Diaz & Grote 2009 in the physical-state form of
  // coupling-study/lts/lts_physical_form.py; in the linear case z_q = (U(T + qh) + U(T - qh)) / 2
  // is the leapfrog LTS substate), frozen at u_J(0) over the first owner step (the start: a
  // genuine initial-value problem on the fine side, coupling-study/lts/README.md).
  const std::size_t n3 = 3 * port.local.size();
  const std::int64_t p = ps.substeps;
  const std::int64_t q = (t1 - ps.T) / h_;
  CRASHLINK_ASSERT(q >= 1 && q <= p);
  const auto row = static_cast<std::size_t>(q);
  const auto mirror = static_cast<std::size_t>(p - q);
  for (std::size_t j = 0; j < port.local.size(); ++j) {
    const std::size_t s = ghost_slot_[port.local[j]];
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t i = 3 * j + d;
      double u = 0.0;
      if (q == p)
        u = ps.u_1[i];
      else if (ps.T == 0)
        u = ps.u_T[i];
      else
        u = 2.0 * ps.u_T[i] - ps.path_prev[mirror * n3 + i];
      ps.path_cur[row * n3 + i] = u;
      ghost_u_[3 * s + d] = u;
      // omega over [t1 - h, t1] (small rotations, Theta reflected as U): the mirror substep's;
      // frozen over the first owner step; over the last substep what lands on the owner's
      // rotation Theta(T) + H omega_J(T + H/2): p omega_J - sum of the substeps' before.
      double w = 0.0;
      if (ps.rotates) {
        const std::size_t sub = row - 1;
        if (q == p) {
          w = static_cast<double>(p) * (ps.omega.empty() ? 0.0 : ps.omega[i]);
          for (std::size_t k = 0; k < sub; ++k) w -= ps.omega_cur[k * n3 + i];
        } else if (ps.T != 0) {
          w = ps.omega_prev[mirror * n3 + i];
        }
        ps.omega_cur[sub * n3 + i] = w;
      }
      ghost_omega_[3 * s + d] = w;
    }
  }
}

bool LayerStepper::lts_owner_instant(Tick t) const {
  if (variable_)  // one owner: the ends of its owner step
    return !follower_ || t == owner_T_ || t == owner_T_ + owner_H_;
  for (const auto& port : ports_)
    if (port.fine_side && t % port.partner_step != 0) return false;
  return true;
}

void LayerStepper::lts_send_forces() {
  if (variable_) {
    lts_send_forces_variable();
    return;
  }
  // At every fine instant t_q = T + q h: the layer's force on J, g = Solver::net_force, into
  // Fbar(T) with weight (p - q) / p^2 and into Fbar(T + H) with q / p^2: the hat
  // (1/p)(1 - |t_q - T| / H) of Diaz & Grote's leapfrog LTS seen from the coarse side
  // (coupling-study/lts/lts_2proc.py: beta_0 = 1/p, beta_q = 2 (p - q) / p^2 split over T +- q h).
  // Over the first owner step the weights are doubled (one-sided: nothing before t = 0), and the
  // last Fbar, at the end of the run, is one-sided too. Fbar(T) leaves after T + (p - 1) h.
  for (std::size_t pi = 0; pi < ports_.size(); ++pi) {
    const auto& port = ports_[pi];
    if (!port.fine_side) continue;
    auto& ps = state_[pi];
    const Tick H = port.partner_step;
    const std::int64_t p = ps.substeps;
    const Tick T = (t_ / H) * H;
    const std::int64_t q = (t_ - T) / h_;
    if (q == 0 && T != ps.acc_T) {
      CRASHLINK_ASSERT(T == ps.acc_T + H);
      ps.fbar_T.swap(ps.fbar_T1);
      std::fill(ps.fbar_T1.begin(), ps.fbar_T1.end(), 0.0);
      ps.mbar_T.swap(ps.mbar_T1);
      std::fill(ps.mbar_T1.begin(), ps.mbar_T1.end(), 0.0);
      ps.acc_T = T;
    }
    const auto pp = static_cast<double>(p * p);
    const double w_now = static_cast<double>(p - q) / pp * (T == 0 && q > 0 ? 2.0 : 1.0);
    const double w_next = static_cast<double>(q) / pp;
    const bool send = q == p - 1;
    const bool ending = q == 0 && p > 1 && finished_here();
    std::vector<double> g_now, m_now;
    if (ending) {
      g_now.resize(ps.fbar_T.size());
      m_now.resize(ps.mbar_T.size());
    }
    for (std::size_t j = 0; j < port.local.size(); ++j) {
      const Vec3 g = solver_.net_force(port.local[j]);
      const Vec3 mo = ps.rotates ? solver_.net_moment(port.local[j]) : Vec3{};
      for (std::size_t d = 0; d < 3; ++d) {
        const std::size_t k = 3 * j + d;
        ps.fbar_T[k] += w_now * g[d];
        if (q > 0) ps.fbar_T1[k] += w_next * g[d];
        if (ending) g_now[k] = g[d];
        if (!ps.rotates) continue;
        ps.mbar_T[k] += w_now * mo[d];
        if (q > 0) ps.mbar_T1[k] += w_next * mo[d];
        if (ending) m_now[k] = mo[d];
      }
    }
    if (!send && !ending) continue;
    // After a restart at an owner instant: the owner's checkpoint is past Fbar(acc_T), and the
    // coordinator's history has its row. Only the meter moves on.
    const bool consumed = ps.consumed == ps.acc_T;
    if (consumed) ps.consumed = -1;
    LayerMessage m;
    m.kind = LayerMessage::Kind::Force;
    m.interface_index = port.index;
    m.time = ps.acc_T;
    m.first = ps.fbar_T;
    m.second = ps.mbar_T;
    if (ending) {  // g/p + 2 S, where fbar_T = g/p + S: the last owner step one-sided
      for (std::size_t k = 0; k < m.first.size(); ++k)
        m.first[k] = 2.0 * ps.fbar_T[k] - g_now[k] / static_cast<double>(p);
      for (std::size_t k = 0; k < m.second.size(); ++k)
        m.second[k] = 2.0 * ps.mbar_T[k] - m_now[k] / static_cast<double>(p);
    }
    if (record_history_) {
      // u_J(acc_T); omega_J(acc_T - H/2), received with it (none at t = 0)
      const auto& uJ = ps.acc_T == ps.T ? ps.u_T : ps.u_1;
      const std::span<const double> omega =
          ps.acc_T == 0 ? std::span<const double>() : std::span<const double>(ps.omega);
      auto row = ps.meter.add(m.time, m.first, m.second, uJ, omega);
      if (!consumed) ps.rows.push_back(std::move(row));
    }
    if (!consumed) outbox_.push_back(std::move(m));
  }
}

void LayerStepper::lts_sample_energy() {
  // E at a wanted instant needs u there and at the two coarse instants before
  const Tick P = energy_period_;
  const auto& want = lts_energy_wanted_;
  const bool evaluate = !want || want(t_);
  if (!evaluate && !want(t_ + P) && !want(t_ + 2 * P)) return;
  lts_energy_.sample(solver_.displacement().data(), t_ / P, evaluate);
  if (!evaluate) return;
  lts_sampled_at_[1] = lts_sampled_at_[0];
  lts_sampled_J_[1] = lts_sampled_J_[0];
  lts_sampled_at_[0] = t_;
  lts_sampled_J_[0] =
      lts_energy_.ready() ? lts_energy_.value_J() : std::numeric_limits<double>::quiet_NaN();
}

void LayerStepper::lts_start_energy() {
  const std::size_t n = solver_.model().nodes.count();
  std::vector<std::uint8_t> owned(n, 1);
  for (const auto g : solver_.ghost_nodes()) owned[static_cast<std::size_t>(g)] = 0;
  // A rigid body's nodes carry its mass, shared in proportion to their lumped masses: the body's
  // translation counts 1/2 M v^2 (its rotation the inertia of those scaled masses, which is the
  // body's unless the scenario gives it).
  std::vector<double> mass(solver_.mass().begin(), solver_.mass().end());
  for (const auto& b : solver_.rigid_bodies()) {
    double sum = 0.0;
    for (const auto i : b.nodes) sum += mass[static_cast<std::size_t>(i)];
    if (sum <= 0.0 || b.mass_kg <= 0.0) continue;
    for (const auto i : b.nodes) mass[static_cast<std::size_t>(i)] *= b.mass_kg / sum;
  }
  lts_energy_.reset(std::move(owned), solver_.model().fixed, std::move(mass),
                    std::vector<double>(solver_.inertia().begin(), solver_.inertia().end()),
                    seconds(energy_period_));
}

}  // namespace crashlink::cosim
