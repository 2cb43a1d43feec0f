// LayerStepper checkpoints (layer_stepper.h save_state / restore_state).
#include <fmt/format.h>

#include "solver/core/errors.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

void LayerStepper::save_state(core::StateWriter& w) const {
  const std::string& dom = solver_.domain_name();
  if (variable_)
    throw ModelError(
        fmt::format("layer stepper '{}': checkpoints of a run with variable layer "
                    "steps are not written yet (the owner steps in use are not "
                    "saved); run with fixed steps to write checkpoints",
                    dom));
  if (phase_ != Phase::Begin || !outbox_.empty()) {
    throw ModelError(
        fmt::format("layer stepper '{}': a checkpoint is taken between two cycles "
                    "with nothing left to send (phase {}, {} messages queued)",
                    dom, static_cast<int>(phase_), outbox_.size()));
  }
  w.put_int("stepper.step", h_);
  w.put_int("stepper.ticks_per_second", ticks_per_second_);
  w.put_int("stepper.time", t_);
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
    w.put_int(pre + "next_expected", ps.inbox.empty() ? ps.next_expected : ps.inbox.front().time);
    w.put(pre + "u_T", std::span<const double>(ps.u_T));
    w.put(pre + "u_1", std::span<const double>(ps.u_1));
    w.put(pre + "omega", std::span<const double>(ps.omega));
    w.put_int(pre + "T", ps.T);
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
  }
  w.put("stepper.ghost_u", std::span<const double>(ghost_u_));
  w.put("stepper.ghost_omega", std::span<const double>(ghost_omega_));
}

void LayerStepper::restore_state(const core::StateReader& r) {
  const std::string& dom = solver_.domain_name();
  if (phase_ != Phase::Initial || initialized_)
    throw ModelError("layer stepper '" + dom + "': restore_state() after initialize()");
  if (r.get_int("stepper.step") != h_ ||
      r.get_int("stepper.ticks_per_second") != ticks_per_second_ ||
      r.get_int("stepper.ports") != static_cast<std::int64_t>(ports_.size())) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: domain '{}' was run with a step of {} ticks of 1/{} s and {} interfaces; "
        "this run plans {} ticks of 1/{} s and {} interfaces. A restart needs the same scenario, "
        "mode and step safety as the run that wrote the checkpoint",
        r.path(), dom, r.get_int("stepper.step"), r.get_int("stepper.ticks_per_second"),
        r.get_int("stepper.ports"), h_, ticks_per_second_, ports_.size()));
  }
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    auto& ps = state_[p];
    const std::string pre = fmt::format("port{}.", p);
    if (r.get_int(pre + "index") != port.index || r.get_bool(pre + "fine_side") != port.fine_side ||
        r.get_int(pre + "partner_step") != port.partner_step) {
      throw CheckpointError(
          fmt::format("checkpoint {}: domain '{}', interface {} was cut or "
                      "stepped differently by the run that wrote it",
                      r.path(), dom, port.index));
    }
    ps.inbox.clear();
    ps.next_expected = r.get_int(pre + "next_expected");
    r.get(pre + "u_T", ps.u_T);
    r.get(pre + "u_1", ps.u_1);
    r.get(pre + "omega", ps.omega);
    ps.T = r.get_int(pre + "T");
    ps.have_u1 = r.get_bool(pre + "have_u1");
    coordinator::LayerWorkState h;
    r.get(pre + "work.g_prev", h.g_prev);
    r.get(pre + "work.u_prev", h.u_prev);
    r.get(pre + "work.m_prev", h.m_prev);
    h.have_prev = r.get_bool(pre + "work.have_prev");
    h.work_J = r.get_double(pre + "work.J");
    ps.meter.restore(std::move(h));
    ps.rows.clear();
  }
  r.get_exact("stepper.ghost_u", ghost_u_);
  r.get_exact("stepper.ghost_omega", ghost_omega_);
  t_ = r.get_int("stepper.time");
  initialized_ = true;
  phase_ = Phase::Begin;
  wait_ = Wait::None;
}

}  // namespace crashlink::cosim
