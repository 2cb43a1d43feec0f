// LayerStepper's steps, ends and pauses (layer_stepper.h "Steps"; docs/design.md §2.6): a variable
// leader's choice of H, a follower's owner steps and substeps, the instants at which a domain
// ends and pauses (advance()'s `until`, checkpoints).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/errors.h"
#include "coupling/domain_scheme.h"
#include "coupling/step_policy.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

void LayerStepper::set_proposal_limits(double leader_safety, double max_step_s) {
  if (!(leader_safety > 0.0 && leader_safety <= 1.0) || !(max_step_s >= 0.0))
    throw ModelError(
        fmt::format("layer stepper '{}': leader safety {} must be in (0, 1] and the "
                    "step cap {} s >= 0",
                    solver_.domain_name(), leader_safety, max_step_s));
  leader_safety_ = leader_safety;
  max_step_s_ = max_step_s;
}

bool LayerStepper::at_owner_instant(const LayerPort& port) const {
  if (!variable_) return t_ % port.partner_step == 0;
  return t_ == 0 || at_owner_end();  // every fine port has the one owner
}

Tick LayerStepper::proposal_ticks() const {
  const double dt = coupling::own_step_s(solver_, max_step_s_);
  if (!std::isfinite(dt) || dt >= 1e3) return 0;  // rigid bodies only: no limit of its own
  if (!(dt * static_cast<double>(ticks_per_second_) >= 1.0))
    throw NumericalError(
        fmt::format("{}: the stable step fell to {:.3e} s, below one tick, at "
                    "t = {} ticks, set by {}: an element is collapsing",
                    solver_.domain_name(), dt, t_, solver_.critical_element()));
  return coupling::TickClock(ticks_per_second_).step_to_ticks(dt);
}

Tick LayerStepper::subtree_proposal() const {
  // The least proposal of this domain and of the holders' g_A(t_) at the inbox fronts (each
  // already its sender's subtree's least); 0 when none has a limit.
  Tick p = proposal_ticks();
  for (std::size_t k = 0; k < ports_.size(); ++k) {
    if (ports_[k].fine_side || state_[k].inbox.empty()) continue;
    const Tick q = state_[k].inbox.front().proposal;
    if (q > 0 && (p == 0 || q < p)) p = q;
  }
  return p;
}

bool LayerStepper::forces_wait_for_holders() const {
  if (!common_ || !follower_) return false;
  return std::any_of(ports_.begin(), ports_.end(), [](const LayerPort& p) { return !p.fine_side; });
}

Tick LayerStepper::choose_step() const {
  if (common_) {  // split: the least proposal of all (LayerSteps, layer_stepper.h)
    const Tick H = subtree_proposal();
    if (H == 0)
      throw ModelError("layer stepper '" + solver_.domain_name() +
                       "': no domain of this coupling has a stable-step limit (rigid bodies "
                       "only?); set controls.dt_max");
    // a mono run's step hold, in whole ticks (exact as doubles), on the step in force
    return static_cast<Tick>(
        integration::held_step(static_cast<double>(H), static_cast<double>(h_)));
  }
  // A leader's next step (LayerSteps, layer_stepper.h; coupling/step_policy.h): the holders'
  // proposals come with g_A(t), one per partner.
  std::vector<coupling::HolderProposal> holders;
  std::vector<std::string> seen;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (port.fine_side || state_[p].inbox.empty()) continue;
    if (std::find(seen.begin(), seen.end(), port.partner) != seen.end()) continue;
    seen.push_back(port.partner);
    holders.push_back({state_[p].inbox.front().proposal,
                       static_cast<double>(std::max<std::size_t>(port.partner_elements, 1))});
  }
  return coupling::leader_step(
      proposal_ticks(), leader_safety_,
      static_cast<double>(std::max<std::size_t>(solver_.model().element_count(), 1)), holders, h_,
      solver_.domain_name());
}

bool LayerStepper::finishes_at(Tick t) const {
  if (!follower_) return t >= end_;
  return t == owner_T_ + owner_H_ && owner_last_;  // with the owner (its u_J(T + H) says so)
}

bool LayerStepper::pauses_at(Tick t) const {
  // (lts: a leader does not pause at its last instant, where its followers, which end there,
  // could not: no u_J marked `last` is marked `pause`)
  if (!follower_) return t_ < until_ && t >= until_ && !(lts_variable() && finishes_at(t));
  return owner_pause_ && t == owner_T_ + owner_H_;
}

bool LayerStepper::pause_here() const {
  if (!variable_ || !follower_) return t_ >= until_ && !(lts_variable() && finished_here());
  // lts: at the start of the owner step that begins where the owner pauses (set when that owner
  // step is taken up, lts_plan_next: its u_J said so)
  if (form_ == LayerForm::Lts) return t_ == lts_pause_at_ && t_ >= until_;
  // where the owner pauses, for as long as the caller's `until` has not passed that instant (a
  // later `until`, the next checkpoint's, lets it go on; a repeated call stays paused)
  return step_pending_ && owner_pause_ && at_owner_end() && t_ >= until_;
}

bool LayerStepper::pausing_now() const {
  return variable_ && !follower_ && t_ >= until_;
}

bool LayerStepper::finished_here() const {
  if (variable_) return finishes_at(t_);
  if (t_ < end_) return false;
  for (const auto& port : ports_)
    if (port.fine_side && !at_owner_instant(port)) return false;  // land with the owner
  return true;
}

bool LayerStepper::at_owner_end() const {
  return owner_H_ > 0 && t_ == owner_T_ + owner_H_;
}

bool LayerStepper::start_owner_step() {
  // A follower at the end of its owner step (or at t = 0): the owner's next u_J(T + H), the
  // front of every fine port's inbox (the one in use was taken by ghost_targets_ready), tells H.
  Tick T1 = -1;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (!port.fine_side) continue;
    const auto& ps = state_[p];
    if (ps.inbox.empty()) {
      wait_iface_ = port.index;
      return false;
    }
    const Tick t = ps.inbox.front().time;
    if (T1 >= 0 && t != T1)
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: the owner '{}' sent u_J for t = {} ticks, another "
          "of its interfaces for t = {} ticks; one owner step must end at one instant",
          solver_.domain_name(), port.index, port.partner, t, T1));
    const bool last = ps.inbox.front().last, pause = ps.inbox.front().pause;
    if (T1 >= 0 && (last != owner_last_ || pause != owner_pause_))
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: the owner '{}' marks its u_J for t = {} ticks with "
          "last = {}, pause = {}, another of its interfaces with {}, {}; one owner step ends or "
          "pauses once",
          solver_.domain_name(), port.index, port.partner, t, last, pause, owner_last_,
          owner_pause_));
    T1 = t;
    owner_last_ = last;
    owner_pause_ = pause;
  }
  if (T1 <= t_)
    throw ModelError(
        fmt::format("layer stepper '{}': the owner's u_J for t = {} ticks is not "
                    "after this domain's instant {} ticks",
                    solver_.domain_name(), T1, t_));
  owner_T_ = t_;
  owner_H_ = T1 - t_;
  substeps_ = proposal_sent_ > 0
                  ? std::max<Tick>(1, owner_H_ / proposal_sent_ + (owner_H_ % proposal_sent_ != 0))
                  : 1;
  substep_ = 0;
  h_ = next_substep();
  return true;
}

}  // namespace crashlink::cosim
