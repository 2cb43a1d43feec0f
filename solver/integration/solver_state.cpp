// Solver checkpoints (solver.h save_state / restore_state; DESIGN.md §2.6 "Checkpoints"): every
// member that evolves during the run, by name. What initialize() rebuilds identically from the
// model (masses, inertias, rigid-body offsets and inertia, prescribed-dof lists, contact segments)
// is not saved; a restarted daemon calls initialize() first, then restore_state().
#include <fmt/format.h>

#include "solver/integration/solver.h"

namespace crashlink::integration {

namespace {

using core::StateReader;
using core::StateWriter;

template <class T>
std::span<const T> cs(const std::vector<T>& v) {
  return std::span<const T>(v);
}

void save_hex(StateWriter& w, const std::string& p, const elements::Hex8State& s) {
  w.put(p + "stress", cs(s.stress));
  w.put(p + "eps_p", cs(s.eps_p));
  w.put(p + "hourglass_force", cs(s.hourglass_force));
  w.put(p + "volume0", cs(s.volume0));
  w.put(p + "bulk_q_Pa", cs(s.bulk_q_Pa));
  w.put(p + "damping_beta_s", cs(s.damping_beta_s));
  w.put(p + "damping_stress_Pa", cs(s.damping_stress_Pa));
  w.put_bool(p + "reference_recorded", s.reference_recorded);
}

void restore_hex(const StateReader& r, const std::string& p, elements::Hex8State& s) {
  r.get_exact(p + "stress", s.stress);
  r.get_exact(p + "eps_p", s.eps_p);
  r.get_exact(p + "hourglass_force", s.hourglass_force);
  r.get(p + "volume0", s.volume0);  // filled by the first force computation
  r.get_exact(p + "bulk_q_Pa", s.bulk_q_Pa);
  r.get(p + "damping_beta_s", s.damping_beta_s);
  r.get(p + "damping_stress_Pa", s.damping_stress_Pa);
  s.reference_recorded = r.get_bool(p + "reference_recorded");
}

void save_shell(StateWriter& w, const std::string& p, const elements::ShellState& s) {
  w.put(p + "sigma_Pa", cs(s.sigma_Pa));
  w.put(p + "eps_p", cs(s.eps_p));
  w.put(p + "resultant_Pa", cs(s.resultant_Pa));
  w.put(p + "shear_Pa", cs(s.shear_Pa));
  w.put(p + "thickness_m", cs(s.thickness_m));
  w.put(p + "bulk_q_Pa", cs(s.bulk_q_Pa));
  w.put(p + "hourglass", cs(s.hourglass));
  w.put(p + "damping_beta_s", cs(s.damping_beta_s));
  w.put(p + "damping_stress_Pa", cs(s.damping_stress_Pa));
  w.put_bool(p + "damping_recorded", s.damping_recorded);
}

void restore_shell(const StateReader& r, const std::string& p, elements::ShellState& s) {
  // The point form may have turned into the resultant form (elastic material): sizes follow.
  r.get(p + "sigma_Pa", s.sigma_Pa);
  r.get(p + "eps_p", s.eps_p);
  r.get(p + "resultant_Pa", s.resultant_Pa);
  r.get_exact(p + "shear_Pa", s.shear_Pa);
  r.get_exact(p + "thickness_m", s.thickness_m);
  r.get_exact(p + "bulk_q_Pa", s.bulk_q_Pa);
  r.get_exact(p + "hourglass", s.hourglass);
  r.get(p + "damping_beta_s", s.damping_beta_s);
  r.get(p + "damping_stress_Pa", s.damping_stress_Pa);
  s.damping_recorded = r.get_bool(p + "damping_recorded");
}

}  // namespace

void Solver::save_state(StateWriter& w) const {
  w.put_string("solver.domain", domain_);
  w.put_int("solver.nodes", static_cast<std::int64_t>(n_));
  w.put("x", cs(x_));
  w.put("u", cs(u_));
  w.put("v", cs(v_));
  w.put("v_prev", cs(v_prev_));
  w.put("a", cs(a_));
  w.put("omega", cs(omega_));
  w.put("omega_prev", cs(omega_prev_));
  w.put("alpha", cs(alpha_));
  w.put("f_int", cs(f_int_));
  w.put("f_ext", cs(f_ext_));
  w.put("m_int", cs(m_int_));
  w.put("f_cont", cs(f_cont_));
  w.put("f_load", cs(f_load_));
  w.put("f_coup", cs(f_coup_));
  w.put("m_coup", cs(m_coup_));
  w.put("dtheta", cs(dtheta_));
  w.put("du", cs(du_));
  w.put("ghost_omega", cs(ghost_omega_));
  w.put_bool("ghost_omega_set", ghost_omega_set_);
  w.put("ghost_target", cs(ghost_target_));
  w.put_bool("ghost_target_set", ghost_target_set_);
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    const PartRuntime& part = parts_[p];
    const std::string pre = fmt::format("part{}.", p);
    w.put_pod(pre + "last", part.last);
    w.put_double(pre + "internal_energy_J", part.internal_energy_J);
    w.put_double(pre + "hourglass_energy_J", part.hourglass_energy_J);
    w.put_double(pre + "damping_energy_J", part.damping_energy_J);
    if (const auto* h = std::get_if<elements::Hex8State>(&part.state)) save_hex(w, pre, *h);
    if (const auto* s = std::get_if<elements::ShellState>(&part.state)) save_shell(w, pre, *s);
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBodyState& s = bodies_[b];
    const std::string pre = fmt::format("body{}.", b);
    w.put_pod(pre + "centre", s.centre);
    w.put_pod(pre + "velocity", s.velocity);
    w.put_pod(pre + "velocity_prev", s.velocity_prev);
    w.put_pod(pre + "angular_momentum", s.angular_momentum);
    w.put_pod(pre + "omega", s.omega);
    w.put_pod(pre + "omega_prev", s.omega_prev);
    w.put_pod(pre + "rotation", s.rotation);
    w.put_pod(pre + "force", s.force);
    w.put_pod(pre + "torque", s.torque);
  }
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    contacts_[k].save_state(w, fmt::format("contact{}.", k));
    w.put_pod(fmt::format("contact{}.step", k), contact_steps_[k]);
  }
  std::vector<double> reactions;
  for (const auto& d : prescribed_) reactions.push_back(d.reaction_prev);
  w.put("prescribed.reaction_prev", cs(reactions));
  w.put_pod("energy", energy_);
  w.put_double("time_s", time_s_);
  w.put_int("cycle", cycle_);
  w.put_double("dt", dt_);
  w.put_double("dt_prev", dt_prev_);
  w.put_double("dt_min", dt_min_);
  w.put_double("dt_stable", dt_stable_);
  w.put_int("critical_part", static_cast<std::int64_t>(critical_part_));
  w.put_int("critical_local", critical_local_);
  w.put_bool("begun", begun_);
  w.put_bool("positions_done", positions_done_);
}

void Solver::restore_state(const StateReader& r) {
  if (r.get_string("solver.domain") != domain_ ||
      r.get_int("solver.nodes") != static_cast<std::int64_t>(n_)) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: written for domain '{}' with {} nodes; this is domain '{}' with {} "
        "nodes: restart with the scenario and the domain that wrote it",
        r.path(), r.get_string("solver.domain"), r.get_int("solver.nodes"), domain_, n_));
  }
  r.get_exact("x", x_);
  r.get_exact("u", u_);
  r.get_exact("v", v_);
  r.get_exact("v_prev", v_prev_);
  r.get_exact("a", a_);
  r.get_exact("omega", omega_);
  r.get_exact("omega_prev", omega_prev_);
  r.get_exact("alpha", alpha_);
  r.get_exact("f_int", f_int_);
  r.get_exact("f_ext", f_ext_);
  r.get_exact("m_int", m_int_);
  r.get_exact("f_cont", f_cont_);
  r.get_exact("f_load", f_load_);
  r.get_exact("f_coup", f_coup_);
  r.get_exact("m_coup", m_coup_);
  r.get_exact("dtheta", dtheta_);
  r.get_exact("du", du_);
  r.get("ghost_omega", ghost_omega_);
  ghost_omega_set_ = r.get_bool("ghost_omega_set");
  r.get("ghost_target", ghost_target_);
  ghost_target_set_ = r.get_bool("ghost_target_set");
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    PartRuntime& part = parts_[p];
    const std::string pre = fmt::format("part{}.", p);
    r.get_pod(pre + "last", part.last);
    part.internal_energy_J = r.get_double(pre + "internal_energy_J");
    part.hourglass_energy_J = r.get_double(pre + "hourglass_energy_J");
    part.damping_energy_J = r.get_double(pre + "damping_energy_J");
    if (auto* h = std::get_if<elements::Hex8State>(&part.state)) restore_hex(r, pre, *h);
    if (auto* s = std::get_if<elements::ShellState>(&part.state)) restore_shell(r, pre, *s);
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    RigidBodyState& s = bodies_[b];
    const std::string pre = fmt::format("body{}.", b);
    r.get_pod(pre + "centre", s.centre);
    r.get_pod(pre + "velocity", s.velocity);
    r.get_pod(pre + "velocity_prev", s.velocity_prev);
    r.get_pod(pre + "angular_momentum", s.angular_momentum);
    r.get_pod(pre + "omega", s.omega);
    r.get_pod(pre + "omega_prev", s.omega_prev);
    r.get_pod(pre + "rotation", s.rotation);
    r.get_pod(pre + "force", s.force);
    r.get_pod(pre + "torque", s.torque);
  }
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    contacts_[k].restore_state(r, fmt::format("contact{}.", k));
    r.get_pod(fmt::format("contact{}.step", k), contact_steps_[k]);
  }
  std::vector<double> reactions(prescribed_.size());
  r.get_exact("prescribed.reaction_prev", reactions);
  for (std::size_t i = 0; i < prescribed_.size(); ++i) prescribed_[i].reaction_prev = reactions[i];
  r.get_pod("energy", energy_);
  time_s_ = r.get_double("time_s");
  cycle_ = r.get_int("cycle");
  dt_ = r.get_double("dt");
  dt_prev_ = r.get_double("dt_prev");
  dt_min_ = r.get_double("dt_min");
  dt_stable_ = r.get_double("dt_stable");
  critical_part_ = static_cast<std::size_t>(r.get_int("critical_part"));
  critical_local_ = r.get_int("critical_local");
  begun_ = r.get_bool("begun");
  positions_done_ = r.get_bool("positions_done");
}

}  // namespace crashlink::integration
