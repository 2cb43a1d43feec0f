// LayerStepper checkpoints (layer_stepper.h save_state / restore_state).
#include <fmt/format.h>

#include <algorithm>
#include <span>
#include <vector>

#include "core/errors.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

void LayerStepper::save_state(core::StateWriter& w) const {
  const std::string& dom = solver_.domain_name();
  if (phase_ != Phase::Begin || !outbox_.empty()) {
    throw ModelError(
        fmt::format("layer stepper '{}': a checkpoint is taken between two cycles "
                    "with nothing left to send (phase {}, {} messages queued)",
                    dom, static_cast<int>(phase_), outbox_.size()));
  }
  if (lts_variable() && follower_ && t_ != owner_T_) {
    throw ModelError(
        fmt::format("layer stepper '{}': a checkpoint of an lts follower with variable steps is "
                    "taken at the start of an owner step; this one is at {} ticks, inside [{}, {}]",
                    dom, t_, owner_T_, owner_T_ + owner_H_));
  }
  if (variable_ && follower_ && !lts_variable() &&
      !(step_pending_ && (t_ == 0 || at_owner_end()))) {
    throw ModelError(
        fmt::format("layer stepper '{}': a checkpoint of a variable follower is taken at the end "
                    "of an owner step; this one is at {} ticks, inside [{}, {}]",
                    dom, t_, owner_T_, owner_T_ + owner_H_));
  }
  w.put_int("stepper.step", h_);
  w.put_int("stepper.ticks_per_second", ticks_per_second_);
  w.put_int("stepper.time", t_);
  w.put_bool("stepper.variable", variable_);
  if (variable_) {
    // Leader: h_ is the step chosen at t_ from the holders' g_A(t_), gone with them. Follower: the
    // owner step just ended (the next one comes with the owner's u_J, sent again) and the
    // proposal sent with g_A(t_), from which it commits its substeps.
    w.put_bool("stepper.step_pending", step_pending_);
    w.put_int("stepper.proposal_sent", proposal_sent_);
    w.put_int("stepper.substeps", substeps_);
    w.put_int("stepper.substep", substep_);
    w.put_int("stepper.owner_T", owner_T_);
    w.put_int("stepper.owner_H", owner_H_);
    w.put_bool("stepper.owner_last", owner_last_);
    w.put_bool("stepper.common", common_);
    w.put_double("stepper.leader_safety", leader_safety_);
    w.put_double("stepper.max_step_s", max_step_s_);
    if (form_ == LayerForm::Lts) {  // the owner steps announced one ahead
      w.put_int("stepper.lts.announced", announced_);
      w.put_bool("stepper.lts.next_owner_known", next_owner_known_);
      w.put_int("stepper.lts.next_owner_H", next_owner_H_);
      w.put_int("stepper.lts.next_substeps", next_substeps_);
      w.put_bool("stepper.lts.owner_pause", owner_pause_);
    }
  }
  w.put_int("stepper.ports", static_cast<std::int64_t>(ports_.size()));
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    const auto& ps = state_[p];
    const std::string pre = fmt::format("port{}.", p);
    for (const auto& m : ps.inbox) {
      if (m.time <= t_) {
        throw ModelError(fmt::format(
            "layer stepper '{}': checkpoint at {} ticks with an unconsumed message for {} ticks "
            "on interface {}",
            dom, t_, m.time, port.index));
      }
    }
    w.put_int(pre + "index", port.index);
    w.put_bool(pre + "fine_side", port.fine_side);
    w.put_int(pre + "partner_step", port.partner_step);
    // The messages received and not used yet go with the checkpoint (an in-process pause leaves
    // the domains at different instants, and their senders will not send them again); the
    // partner's repeats of earlier ones are dropped after the restore (deliver, drop_before).
    w.put_int(pre + "next_expected", ps.next_expected);
    w.put_int(pre + "inbox", static_cast<std::int64_t>(ps.inbox.size()));
    for (std::size_t j = 0; j < ps.inbox.size(); ++j) {
      const auto& m = ps.inbox[j];
      const std::string mp = fmt::format("{}inbox{}.", pre, j);
      w.put_int(mp + "kind", static_cast<std::int64_t>(m.kind));
      w.put_int(mp + "time", m.time);
      w.put_int(mp + "proposal", m.proposal);
      w.put_bool(mp + "last", m.last);
      w.put_bool(mp + "pause", m.pause);
      w.put_int(mp + "next_step", m.next_step);
      w.put(mp + "first", std::span<const double>(m.first));
      w.put(mp + "second", std::span<const double>(m.second));
    }
    w.put(pre + "u_T", std::span<const double>(ps.u_T));
    w.put(pre + "u_1", std::span<const double>(ps.u_1));
    w.put(pre + "omega", std::span<const double>(ps.omega));
    w.put_int(pre + "T", ps.T);
    w.put_int(pre + "T1", ps.T1);
    w.put_bool(pre + "have_u1", ps.have_u1);
    if (!ps.rows.empty()) {
      throw ModelError(
          fmt::format("layer stepper '{}': checkpoint at {} ticks with {} history rows "
                      "of interface {} not reported",
                      dom, t_, ps.rows.size(), port.index));
    }
    const auto& h = ps.meter.state();
    w.put(pre + "work.g_prev", std::span<const double>(h.g_prev));
    w.put(pre + "work.u_prev", std::span<const double>(h.u_prev));
    w.put(pre + "work.m_prev", std::span<const double>(h.m_prev));
    w.put_bool(pre + "work.have_prev", h.have_prev);
    w.put_double(pre + "work.J", h.work_J);
    if (form_ == LayerForm::Lts && port.fine_side) {
      w.put(pre + "lts.path_prev", std::span<const double>(ps.path_prev));
      w.put(pre + "lts.path_cur", std::span<const double>(ps.path_cur));
      w.put(pre + "lts.fbar_T", std::span<const double>(ps.fbar_T));
      w.put(pre + "lts.fbar_T1", std::span<const double>(ps.fbar_T1));
      w.put_int(pre + "lts.acc_T", ps.acc_T);
      w.put(pre + "lts.omega_prev", std::span<const double>(ps.omega_prev));
      w.put(pre + "lts.omega_cur", std::span<const double>(ps.omega_cur));
      w.put(pre + "lts.mbar_T", std::span<const double>(ps.mbar_T));
      w.put(pre + "lts.mbar_T1", std::span<const double>(ps.mbar_T1));
      if (variable_) {
        w.put(pre + "lts.path_prev_t", std::span<const Tick>(ps.path_prev_t));
        w.put(pre + "lts.path_cur_t", std::span<const Tick>(ps.path_cur_t));
        w.put(pre + "lts.fbar_left", std::span<const double>(ps.fbar_left));
        w.put(pre + "lts.g_T", std::span<const double>(ps.g_T));
        w.put(pre + "lts.mbar_left", std::span<const double>(ps.mbar_left));
        w.put(pre + "lts.m_T", std::span<const double>(ps.m_T));
        w.put_int(pre + "lts.H_prev", ps.H_prev);
        w.put_int(pre + "lts.next_step_1", ps.next_step_1);
        w.put_bool(pre + "lts.last_1", ps.last_1);
        w.put_bool(pre + "lts.pause_1", ps.pause_1);
      }
    }
  }
  w.put_int("stepper.form", static_cast<std::int64_t>(form_));
  if (form_ == LayerForm::Lts && !variable_) {
    lts_energy_.save(w, "stepper.lts_energy.");
    w.put_int("stepper.lts_sampled_at0", lts_sampled_at_[0]);
    w.put_int("stepper.lts_sampled_at1", lts_sampled_at_[1]);
    w.put("stepper.lts_sampled_J", std::span<const double>(lts_sampled_J_, 2));
  }
  w.put("stepper.ghost_u", std::span<const double>(ghost_u_));
  w.put("stepper.ghost_omega", std::span<const double>(ghost_omega_));
}

void LayerStepper::restore_state(const core::StateReader& r) {
  const std::string& dom = solver_.domain_name();
  if (phase_ != Phase::Initial || initialized_)
    throw ModelError("layer stepper '" + dom + "': restore_state() after initialize()");
  if (r.get_bool("stepper.variable") != variable_) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' was run with {} steps, this run has {} steps; restart {} "
        "--variable-steps, as the run that wrote the checkpoint",
        r.path(), dom, variable_ ? "fixed" : "variable", variable_ ? "variable" : "fixed",
        variable_ ? "without" : "with"));
  }
  if (variable_ && r.get_bool("stepper.common") != common_) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' was run in `{}` with variable steps, this run is `{}`; "
        "restart with --mode {}, as the run that wrote the checkpoint",
        r.path(), dom, common_ ? "multi" : "split", common_ ? "split" : "multi",
        common_ ? "multi" : "split"));
  }
  // (split: the least proposal of all, no step safety; multi: the leader's step safety)
  if (variable_ && ((!common_ && r.get_double("stepper.leader_safety") != leader_safety_) ||
                    r.get_double("stepper.max_step_s") != max_step_s_)) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' chose its steps with a step safety of {} and a step cap of "
        "{} s; this run has {} and {} s. Variable steps go on from the checkpoint by the same "
        "rule only with the same --step-safety and --max-step: restart with those",
        r.path(), dom, r.get_double("stepper.leader_safety"), r.get_double("stepper.max_step_s"),
        leader_safety_, max_step_s_));
  }
  if ((!variable_ && r.get_int("stepper.step") != h_) ||
      r.get_int("stepper.ticks_per_second") != ticks_per_second_ ||
      r.get_int("stepper.ports") != static_cast<std::int64_t>(ports_.size())) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' was run with a step of {} ticks of 1/{} s and {} interfaces; "
        "this run plans {} ticks of 1/{} s and {} interfaces. A restart needs the same scenario, "
        "mode and step safety as the run that wrote the checkpoint",
        r.path(), dom, r.get_int("stepper.step"), r.get_int("stepper.ticks_per_second"),
        r.get_int("stepper.ports"), h_, ticks_per_second_, ports_.size()));
  }
  const std::int64_t form = r.has("stepper.form") ? r.get_int("stepper.form") : 0;
  if (form != static_cast<std::int64_t>(form_))
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' was run with --coupling {}, this run has --coupling {}; "
        "restart with the coupling of the run that wrote it",
        r.path(), dom, form == 1 ? "lts" : "layer", form_ == LayerForm::Lts ? "lts" : "layer"));
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    auto& ps = state_[p];
    const std::string pre = fmt::format("port{}.", p);
    // (variable steps: partner_step is the planned first step, which the run does not use)
    if (r.get_int(pre + "index") != port.index || r.get_bool(pre + "fine_side") != port.fine_side ||
        (!variable_ && r.get_int(pre + "partner_step") != port.partner_step)) {
      throw CheckpointError(
          fmt::format("checkpoint {}: domain '{}', interface {} was cut or "
                      "stepped differently by the run that wrote it",
                      r.path(), dom, port.index));
    }
    ps.inbox.clear();
    ps.next_expected = r.get_int(pre + "next_expected");
    // (checkpoints before 2026-11-28 hold no inbox: next_expected was its first message's, and
    // the partner sends it again)
    const std::int64_t kept = r.has(pre + "inbox") ? r.get_int(pre + "inbox") : 0;
    const Tick t_saved = r.get_int("stepper.time");
    for (std::int64_t j = 0; j < kept; ++j) {
      const std::string mp = fmt::format("{}inbox{}.", pre, j);
      LayerMessage m;
      m.kind = static_cast<LayerMessage::Kind>(r.get_int(mp + "kind"));
      m.interface_index = port.index;
      m.time = r.get_int(mp + "time");
      m.proposal = r.get_int(mp + "proposal");
      m.last = r.get_bool(mp + "last");
      m.pause = r.get_bool(mp + "pause");
      m.next_step = r.has(mp + "next_step") ? r.get_int(mp + "next_step") : 0;
      r.get(mp + "first", m.first);
      r.get(mp + "second", m.second);
      // what deliver() checks of a message: its kind, its size, its order; and that it is ahead
      const auto want =
          port.fine_side ? LayerMessage::Kind::Displacement : LayerMessage::Kind::Force;
      const std::size_t n3 = 3 * port.local.size();
      if (m.kind != want || m.first.size() != n3 || !(m.second.empty() || m.second.size() == n3) ||
          m.time <= t_saved || (!ps.inbox.empty() && m.time <= ps.inbox.back().time) ||
          m.time >= ps.next_expected)
        throw CheckpointError(fmt::format(
            "checkpoint {}: domain '{}', interface {}: kept message {} (a {} for t = {} ticks, "
            "{} + {} values) does not fit the stepper at t = {} ticks; the file was not written "
            "by this run's stepper",
            r.path(), dom, port.index, j,
            m.kind == LayerMessage::Kind::Displacement ? "displacement" : "force", m.time,
            m.first.size(), m.second.size(), t_saved));
      ps.inbox.push_back(std::move(m));
    }
    ps.drop_before = ps.next_expected;  // (deliver: what the partner sends again)
    r.get(pre + "u_T", ps.u_T);
    r.get(pre + "u_1", ps.u_1);
    r.get(pre + "omega", ps.omega);
    ps.T = r.get_int(pre + "T");
    ps.T1 = r.get_int(pre + "T1");
    ps.have_u1 = r.get_bool(pre + "have_u1");
    coupling::LayerWorkState h;
    r.get(pre + "work.g_prev", h.g_prev);
    r.get(pre + "work.u_prev", h.u_prev);
    r.get(pre + "work.m_prev", h.m_prev);
    h.have_prev = r.get_bool(pre + "work.have_prev");
    h.work_J = r.get_double(pre + "work.J");
    ps.meter.restore(std::move(h));
    ps.rows.clear();
    if (form_ == LayerForm::Lts && port.fine_side) {
      // Fixed steps: the sizes of the plan, checked on reading; variable: as saved (they follow
      // the owner steps), checked below.
      if (!variable_) lts_start_port(port, ps);
      const auto read = [&](const char* key, std::vector<double>& v) {
        if (variable_)
          r.get(pre + key, v);
        else
          r.get_exact(pre + key, v);
      };
      read("lts.path_prev", ps.path_prev);
      read("lts.path_cur", ps.path_cur);
      read("lts.fbar_T", ps.fbar_T);
      read("lts.fbar_T1", ps.fbar_T1);
      ps.acc_T = r.get_int(pre + "lts.acc_T");
      read("lts.omega_prev", ps.omega_prev);
      read("lts.omega_cur", ps.omega_cur);
      read("lts.mbar_T", ps.mbar_T);
      read("lts.mbar_T1", ps.mbar_T1);
      if (!variable_) {
        // A checkpoint at an owner instant T: the owner's is written after it used Fbar(T),
        // which this side sends only p - 1 substeps later (layer_stepper_lts.cpp): not again.
        ps.consumed = t_saved > 0 && ps.substeps > 1 && t_saved % port.partner_step == 0 &&
                              ps.acc_T == t_saved
                          ? t_saved
                          : -1;
        continue;
      }
      r.get(pre + "lts.path_prev_t", ps.path_prev_t);
      r.get(pre + "lts.path_cur_t", ps.path_cur_t);
      read("lts.fbar_left", ps.fbar_left);
      read("lts.g_T", ps.g_T);
      read("lts.mbar_left", ps.mbar_left);
      read("lts.m_T", ps.m_T);
      ps.H_prev = r.get_int(pre + "lts.H_prev");
      ps.next_step_1 = r.get_int(pre + "lts.next_step_1");
      ps.last_1 = r.get_bool(pre + "lts.last_1");
      ps.pause_1 = r.get_bool(pre + "lts.pause_1");
      // The path holds the owner step this side is in or has just ended (at a pause, the next
      // one is taken up and its rows come at its first substep): sizes checked against
      // themselves and the J nodes, not against the substeps of the step taken up.
      const std::size_t n3 = 3 * port.local.size(), r3 = ps.rotates ? n3 : 0;
      const std::size_t cur = ps.path_cur_t.size(), prev = ps.path_prev_t.size();
      const bool fits = cur >= 2 && prev >= 2 && ps.path_cur.size() == cur * n3 &&
                        ps.path_prev.size() == prev * n3 && ps.omega_cur.size() == (cur - 1) * r3 &&
                        ps.omega_prev.size() == (prev - 1) * r3 && ps.fbar_T.size() == n3 &&
                        ps.fbar_T1.size() == n3 && ps.fbar_left.size() == n3 &&
                        ps.g_T.size() == n3 && ps.mbar_T.size() == r3 && ps.mbar_T1.size() == r3 &&
                        ps.mbar_left.size() == r3 && ps.m_T.size() == r3;
      if (!fits)
        throw CheckpointError(fmt::format(
            "checkpoint {}: domain '{}', interface {}: the lts path and forces ({} and {} rows of "
            "{} and {} values, {} forces) do not fit {} J nodes; the file was not written by this "
            "run's stepper",
            r.path(), dom, port.index, cur, prev, ps.path_cur.size(), ps.path_prev.size(),
            ps.fbar_T.size(), port.local.size()));
      // At the start of an owner step T: the owner's checkpoint is past Fbar(T), which this side
      // sends p - 1 substeps later (layer_stepper_lts_variable.cpp), p the substeps of the owner
      // step taken up at T: not again.
      const std::int64_t p_new = r.get_int("stepper.substeps");
      ps.consumed = t_saved > 0 && p_new > 1 && ps.acc_T == t_saved ? t_saved : -1;
    }
  }
  if (form_ == LayerForm::Lts && !variable_) {
    lts_start_energy();
    lts_energy_.restore(r, "stepper.lts_energy.");
    if (r.has("stepper.lts_sampled_J")) {  // (checkpoints before 2026-11-28: the rows' NaN)
      lts_sampled_at_[0] = r.get_int("stepper.lts_sampled_at0");
      lts_sampled_at_[1] = r.get_int("stepper.lts_sampled_at1");
      std::vector<double> v(2);
      r.get_exact("stepper.lts_sampled_J", v);
      std::copy(v.begin(), v.end(), lts_sampled_J_);
    }
  }
  r.get_exact("stepper.ghost_u", ghost_u_);
  r.get_exact("stepper.ghost_omega", ghost_omega_);
  t_ = r.get_int("stepper.time");
  if (variable_) {
    h_ = r.get_int("stepper.step");
    step_pending_ = r.get_bool("stepper.step_pending");
    proposal_sent_ = r.get_int("stepper.proposal_sent");
    substeps_ = r.get_int("stepper.substeps");
    substep_ = r.get_int("stepper.substep");
    owner_T_ = r.get_int("stepper.owner_T");
    owner_H_ = r.get_int("stepper.owner_H");
    owner_last_ = r.get_bool("stepper.owner_last");
    owner_pause_ = false;  // the pause it was written at is behind
    if (form_ == LayerForm::Lts) {
      announced_ = r.get_int("stepper.lts.announced");
      next_owner_known_ = r.get_bool("stepper.lts.next_owner_known");
      next_owner_H_ = r.get_int("stepper.lts.next_owner_H");
      next_substeps_ = r.get_int("stepper.lts.next_substeps");
      owner_pause_ = r.get_bool("stepper.lts.owner_pause");
      lts_pause_at_ = -1;
    }
  }
  initialized_ = true;
  phase_ = Phase::Begin;
  wait_ = Wait::None;
}

}  // namespace crashlink::cosim
