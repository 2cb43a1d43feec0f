#include "coupling/step_policy.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/integration/step_hold.h"

namespace crashlink::coupling {

Tick leader_step(Tick own, double leader_safety, double own_cost,
                 std::span<const HolderProposal> holders, Tick last, const std::string& domain) {
  if (own > 0 && leader_safety < 1.0)
    own = std::max<Tick>(1, static_cast<Tick>(leader_safety * static_cast<double>(own)));
  if (own == 0)
    for (const auto& k : holders) own = std::max(own, k.proposal);
  if (own == 0)
    throw ModelError("layer stepper '" + domain +
                     "': no domain of this coupling has a stable-step limit (rigid bodies only?); "
                     "set controls.dt_max");
  // Cost per unit time of a step H: own cycles plus each holder's substeps per H.
  auto rate = [&](Tick H) {
    double c = own_cost;
    for (const auto& k : holders)
      c += k.cost * static_cast<double>(k.proposal > 0 ? (H + k.proposal - 1) / k.proposal : 1);
    return c / static_cast<double>(H);
  };
  std::vector<Tick> candidates{own};
  for (const auto& k : holders)
    if (k.proposal > 0 && k.proposal <= own) candidates.push_back((own / k.proposal) * k.proposal);
  Tick best = own;
  double best_rate = rate(own);
  for (const Tick H : candidates) {
    const double r = rate(H);
    if (r < best_rate || (r == best_rate && H > best)) {
      best = H;
      best_rate = r;
    }
  }
  // Hysteresis: the candidate nearest the last step stays unless another one is cheaper by more
  // than kSwitchGain (two nearly equal costs must not make the step jump back and forth).
  if (last > 0) {
    Tick near = own;
    for (const Tick H : candidates)
      if (std::abs(H - last) < std::abs(near - last)) near = H;
    if (rate(near) <= (1.0 + kSwitchGain) * best_rate) best = near;
  }
  // Up toward that target by at most kStepChange per step; down at once: a holder's falling
  // proposal must shrink H with it, or its substep count would jump instead.
  if (last > 0)
    best = std::min(
        best, last + std::max<Tick>(1, static_cast<Tick>(kStepChange * static_cast<double>(last))));
  // The step hold (docs/elements.md "Step hold"): a rise of less than kStepHold keeps the last
  // step, so the step does not follow the vibration's jitter of the proposals and pump energy.
  if (last > 0)
    best = static_cast<Tick>(
        integration::held_step(static_cast<double>(best), static_cast<double>(last)));
  return best;
}

std::vector<Tick> lts_variable_first_proposals(const std::vector<Tick>& proposal,
                                               const std::vector<Tick>& raw,
                                               const std::vector<std::pair<int, int>>& links,
                                               const std::vector<double>& cost,
                                               const std::vector<std::string>& names) {
  const std::size_t n = proposal.size();
  std::vector<char> is_fine(n, 0);
  for (const auto& [c, f] : links) is_fine[static_cast<std::size_t>(f)] = 1;
  std::vector<Tick> out = raw;
  for (std::size_t k = 0; k < n; ++k) {
    if (is_fine[k]) continue;
    out[k] = proposal[k];
    // one per partner, each with its own proposal: what its Fbar carries under lts with variable
    // steps (LayerStepper::choose_step)
    std::vector<HolderProposal> holders;
    std::vector<int> seen;
    for (const auto& [c, f] : links) {
      if (static_cast<std::size_t>(c) != k || std::find(seen.begin(), seen.end(), f) != seen.end())
        continue;
      seen.push_back(f);
      holders.push_back(
          {raw[static_cast<std::size_t>(f)], std::max(cost[static_cast<std::size_t>(f)], 1.0)});
    }
    if (holders.empty()) continue;
    out[k] = leader_step(proposal[k], 1.0, std::max(cost[k], 1.0), holders, 0,
                         k < names.size() ? names[k] : std::to_string(k));
  }
  // A follower never steps longer than its owner (one substep of the owner step): capped here, or
  // nested_steps would take its larger proposal as the base and halve its owner's step. Down the
  // tree: a pass per level.
  for (std::size_t pass = 0; pass < n; ++pass) {
    bool changed = false;
    for (const auto& [c, f] : links) {
      const Tick owner = out[static_cast<std::size_t>(c)];
      Tick& mine = out[static_cast<std::size_t>(f)];
      if (owner > 0 && mine > owner) {
        mine = owner;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return out;
}

}  // namespace crashlink::coupling
