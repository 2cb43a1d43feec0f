#pragma once
// The step hold (docs/elements.md "Step hold"): a stable step that follows the vibration it
// limits, by parts in 10^5, makes central differences pump energy; holding the step in force
// against small rises keeps the leapfrog's long-time energy behaviour.

namespace crashlink::integration {

/// A proposal that exceeds the step in force by less than this fraction keeps the step: one
/// domain's own steps (Solver::set_step_hold), a split run's common step
/// (cosim::LayerStepper::choose_step) and a multi leader's (coupling::leader_step).
inline constexpr double kStepHold = 1e-3;

/// The step to take under the hold: `in_force` when proposal is in [in_force, in_force (1 +
/// kStepHold)), else `proposal` (at once when it is smaller, so never above it). Seconds or ticks;
/// in_force 0 (no step yet): the proposal.
inline double held_step(double proposal, double in_force) {
  return proposal >= in_force && proposal < in_force * (1.0 + kStepHold) ? in_force : proposal;
}

}  // namespace crashlink::integration
