// Solver checkpoints (solver.h save_state / restore_state; docs/design.md §2.6 "Checkpoints"):
// every member that evolves during the run, by name, in ONE list (visit_state) that saving and
// loading both walk. What initialize() rebuilds identically from the model (masses, inertias,
// rigid-body offsets and inertia, prescribed-dof lists, contact segments) is not saved; a restarted
// daemon calls initialize() first, then restore_state().
#include <fmt/format.h>

#include "solver/integration/solver.h"

namespace crashlink::integration {

namespace {

/// Hex8State or const Hex8State. volume0 and the damping arrays are filled by the first force
/// computation: their length is the record's.
template <class V, class H>
void visit_hex(V& v, const std::string& p, H& s) {
  v.sized(p + "stress", s.stress);
  v.sized(p + "eps_p", s.eps_p);
  v.sized(p + "hourglass_force", s.hourglass_force);
  v.vec(p + "volume0", s.volume0);
  v.sized(p + "bulk_q_Pa", s.bulk_q_Pa);
  v.vec(p + "damping_beta_s", s.damping_beta_s);
  v.vec(p + "damping_stress_Pa", s.damping_stress_Pa);
  v.flag(p + "reference_recorded", s.reference_recorded);
}

/// ShellState or const ShellState. The point form may have turned into the resultant form
/// (elastic material): those lengths are the record's.
template <class V, class S>
void visit_shell(V& v, const std::string& p, S& s) {
  v.vec(p + "sigma_Pa", s.sigma_Pa);
  v.vec(p + "eps_p", s.eps_p);
  v.vec(p + "resultant_Pa", s.resultant_Pa);
  v.sized(p + "shear_Pa", s.shear_Pa);
  v.sized(p + "thickness_m", s.thickness_m);
  v.sized(p + "bulk_q_Pa", s.bulk_q_Pa);
  v.sized(p + "hourglass", s.hourglass);
  v.vec(p + "damping_beta_s", s.damping_beta_s);
  v.vec(p + "damping_stress_Pa", s.damping_stress_Pa);
  v.flag(p + "damping_recorded", s.damping_recorded);
}

template <class V, class B>
void visit_body(V& v, const std::string& p, B& s) {
  v.pod(p + "centre", s.centre);
  v.pod(p + "velocity", s.velocity);
  v.pod(p + "velocity_prev", s.velocity_prev);
  v.pod(p + "angular_momentum", s.angular_momentum);
  v.pod(p + "omega", s.omega);
  v.pod(p + "omega_prev", s.omega_prev);
  v.pod(p + "rotation", s.rotation);
  v.pod(p + "force", s.force);
  v.pod(p + "torque", s.torque);
  if (s.breakable) v.pod(p + "failed", s.failed);  // a spot weld (older files hold none)
}

}  // namespace

template <class V, class Self>
void Solver::visit_state(V& v, Self& s) {
  v.sized("x", s.x_);
  v.sized("u", s.u_);
  v.sized("v", s.v_);
  v.sized("v_prev", s.v_prev_);
  v.sized("a", s.a_);
  v.sized("omega", s.omega_);
  v.sized("omega_prev", s.omega_prev_);
  v.sized("alpha", s.alpha_);
  v.sized("f_int", s.f_int_);
  v.sized("f_ext", s.f_ext_);
  v.sized("m_int", s.m_int_);
  v.sized("f_cont", s.f_cont_);
  v.sized("f_coup", s.f_coup_);
  v.sized("m_coup", s.m_coup_);
  if constexpr (V::loading) s.rebuild_coupled_nodes();
  if constexpr (V::loading) {
    v.sized("dtheta", s.dtheta_);
    v.sized("du", s.du_);
    s.increments_everywhere_ = true;  // every dof's, until the next displacement update
  } else {  // every dof's: where the run does not store them, du_at's and dtheta_at's
    std::vector<double> dtheta(s.dtheta_.size()), du(s.du_.size());
    for (std::size_t k = 0; k < du.size(); ++k) {
      dtheta[k] = s.dtheta_at(k);
      du[k] = s.du_at(k);
    }
    v.sized("dtheta", dtheta);
    v.sized("du", du);
  }
  v.vec("ghost_omega", s.ghost_omega_);
  v.flag("ghost_omega_set", s.ghost_omega_set_);
  v.vec("ghost_target", s.ghost_target_);
  v.flag("ghost_target_set", s.ghost_target_set_);
  for (std::size_t p = 0; p < s.parts_.size(); ++p) {
    auto& part = s.parts_[p];
    const std::string pre = fmt::format("part{}.", p);
    v.pod(pre + "last", part.last);
    v.num(pre + "internal_energy_J", part.internal_energy_J);
    v.num(pre + "hourglass_energy_J", part.hourglass_energy_J);
    v.num(pre + "damping_energy_J", part.damping_energy_J);
    if (auto* h = std::get_if<elements::Hex8State>(&part.state)) visit_hex(v, pre, *h);
    if (auto* sh = std::get_if<elements::ShellState>(&part.state)) visit_shell(v, pre, *sh);
  }
  for (std::size_t b = 0; b < s.bodies_.size(); ++b)
    visit_body(v, fmt::format("body{}.", b), s.bodies_[b]);
  if constexpr (V::loading) s.contact_nodes_.reset(s.n_);
  for (std::size_t k = 0; k < s.contacts_.size(); ++k) {
    const std::string pre = fmt::format("contact{}.", k);
    if constexpr (V::loading) {
      s.contacts_[k].restore_state(v.r, pre);
      s.add_contact_nodes(k);  // f_cont's nodes, in the order the run had them
    } else {
      s.contacts_[k].save_state(v.w, pre);
    }
    v.pod(pre + "step", s.contact_steps_[k]);
  }
  std::vector<double> reactions;
  for (const auto& d : s.prescribed_) reactions.push_back(d.reaction_prev);
  v.sized("prescribed.reaction_prev", reactions);
  if constexpr (V::loading) {
    for (std::size_t i = 0; i < reactions.size(); ++i)
      s.prescribed_[i].reaction_prev = reactions[i];
  }
  if (!s.body_motions_.empty()) {  // (checkpoints of models without them keep their layout)
    std::vector<double> body_reactions;
    for (const auto& d : s.body_motions_) body_reactions.push_back(d.reaction_prev);
    v.sized("body_motion.reaction_prev", body_reactions);
    if constexpr (V::loading) {
      for (std::size_t i = 0; i < body_reactions.size(); ++i)
        s.body_motions_[i].reaction_prev = body_reactions[i];
    }
  }
  for (std::size_t k = 0; k < s.walls_.size(); ++k) {
    v.sized(fmt::format("wall{}.reaction_prev", k), s.walls_[k].reaction_prev);
    v.pod(fmt::format("wall{}.force", k), s.walls_[k].force_N);
    v.num(fmt::format("wall{}.work", k), s.walls_[k].work_J);
    v.num(fmt::format("wall{}.travel", k), s.walls_[k].travel_m);
    v.num(fmt::format("wall{}.velocity", k), s.walls_[k].velocity_m_s);
  }
  if (s.global_.on) {  // the global stable step (checkpoints of runs without it keep their layout)
    auto& g = s.global_;
    std::vector<double> ritz = g.lanczos.vector();
    v.sized("global.lanczos_vector", ritz);
    if constexpr (V::loading) g.lanczos.set_vector(ritz);
    for (std::size_t p = 0; p < g.ref_inv.size(); ++p)
      v.sized(fmt::format("global.ref_inv{}", p), g.ref_inv[p]);
    v.num("global.dt_global", g.dt_global_s);
    v.num("global.probe_dt", g.probe_dt_s);
    v.num("global.ratio", g.ratio);
    v.num("global.ratio_at_refresh", g.ratio_at_refresh);
    v.integer("global.ratio_part", g.ratio_part);
    v.integer("global.ratio_element", g.ratio_element);
    v.integer("global.refresh_cycle", g.refresh_cycle);
    v.flag("global.binds", g.binds);
  }
  v.pod("energy", s.energy_);
  v.num("time_s", s.time_s_);
  v.integer("cycle", s.cycle_);
  v.num("dt", s.dt_);
  v.num("dt_prev", s.dt_prev_);
  v.num("dt_min", s.dt_min_);
  v.num("dt_stable", s.dt_stable_);
  v.integer("critical_part", s.critical_part_);
  v.integer("critical_local", s.critical_local_);
  v.flag("begun", s.begun_);
  v.flag("positions_done", s.positions_done_);
}

void Solver::save_state(core::StateWriter& w) const {
  w.put_string("solver.domain", domain_);
  w.put_int("solver.nodes", static_cast<std::int64_t>(n_));
  core::StateSave v{w};
  visit_state(v, *this);
  // the spot welds that let go so far (for the run's summary and result.h5): written only when
  // some did, so that older checkpoints and runs without failures keep their layout
  if (!weld_failures_.empty()) {
    w.put_int("weld_failures.count", static_cast<std::int64_t>(weld_failures_.size()));
    for (std::size_t k = 0; k < weld_failures_.size(); ++k) {
      const auto& f = weld_failures_[k];
      const std::string pre = fmt::format("weld_failures.{}.", k);
      w.put_string(pre + "name", f.name);
      w.put_double(pre + "time", f.time_s);
      w.put_double(pre + "normal", f.normal_N);
      w.put_double(pre + "shear", f.shear_N);
    }
  }
}

void Solver::restore_state(const core::StateReader& r) {
  if (r.get_string("solver.domain") != domain_ ||
      r.get_int("solver.nodes") != static_cast<std::int64_t>(n_)) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: written for domain '{}' with {} nodes; this is domain '{}' with {} "
        "nodes: restart with the scenario and the domain that wrote it",
        r.path(), r.get_string("solver.domain"), r.get_int("solver.nodes"), domain_, n_));
  }
  core::StateLoad v{r};
  visit_state(v, *this);
  weld_failures_.clear();
  if (r.has("weld_failures.count"))
    for (std::int64_t k = 0; k < r.get_int("weld_failures.count"); ++k) {
      const std::string pre = fmt::format("weld_failures.{}.", k);
      weld_failures_.push_back({r.get_string(pre + "name"), r.get_double(pre + "time"),
                                r.get_double(pre + "normal"), r.get_double(pre + "shear")});
    }
  // a spot weld that had let go: its nodes move on their own again
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    if (bodies_[b].failed) {
      bodies_[b].failed = 0;
      release_body(b, /*accelerate=*/false);
    }
}

}  // namespace crashlink::integration
