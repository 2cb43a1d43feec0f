#pragma once
// How a `layer` domain with variable steps chooses its next step (docs/multirate.md "Variable
// steps"), as pure functions of the proposals, so that the policy is tested on its own:
//   - common (split): every domain at the least proposal of all;
//   - a leader's (multi): its own proposal, or a whole multiple of a holder's proposal below it,
//     whichever costs least per unit of simulated time (cost: elements x cycles), kept near the
//     last step unless another is cheaper by more than kSwitchGain (hysteresis), raised by at
//     most kStepChange of the last step per step (ramp), held against rises under
//     integration::kStepHold (solver/integration/step_hold.h); lowered at once.
// Fixed steps need no policy: the plan (nested_steps.h) is kept for the whole run.
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "coupling/ticks.h"

namespace crashlink::coupling {

/// A leader's step changes by at most this fraction of the last step per step: a jump of the step
/// by x costs the central-difference energy balance about x / 2 of that step's work ([2]).
inline constexpr double kStepChange = 0.02;
/// A leader changes to a cheaper kind of step only for more than this gain.
inline constexpr double kSwitchGain = 0.05;

/// One domain holding ghosts of the leader: its subtree's least proposal (ticks, 0: no limit) and
/// its cost per cycle (its element count).
struct HolderProposal {
  Tick proposal = 0;
  double cost = 1.0;
};

/// The leader's next step H in ticks. own: its own proposal (0: no limit), scaled here by
/// leader_safety in (0, 1] (at least one tick); own_cost its element count; last the step just
/// taken (0: the first). Throws ModelError naming `domain` when neither it nor a holder has a
/// limit (rigid bodies only).
Tick leader_step(Tick own, double leader_safety, double own_cost,
                 std::span<const HolderProposal> holders, Tick last, const std::string& domain);

/// `lts` with variable steps (docs/multirate.md "Variable steps under lts"): the plan gives the
/// first owner step, and each leader's rule (leader_step) the later ones. Where the plan's ceil
/// rule (nested_steps) and the cost rule chose different kinds of step (p = 3 at the leader's own
/// proposal against p = 2 at twice a holder's), the fine step jumped by up to half at the end of
/// the first owner step, and with it the central-difference energy ([2]): -4.4 % of balance on
/// a bar whose end plane starts at 30 m/s. The proposals nested_steps is then to plan with,
/// those the steppers' rule sees at t = 0: a leader's (a domain that is no link's fine side)
/// leader_step's choice from its `proposal` (the step safety in it, as a leader takes it) and
/// from its holders' own `raw` proposals (without it, as each follower's Fbar carries its own)
/// and element counts (`cost`); every other domain's its `raw` one, capped at its owner's.
std::vector<Tick> lts_variable_first_proposals(const std::vector<Tick>& proposal,
                                               const std::vector<Tick>& raw,
                                               const std::vector<std::pair<int, int>>& links,
                                               const std::vector<double>& cost,
                                               const std::vector<std::string>& names);

}  // namespace crashlink::coupling
