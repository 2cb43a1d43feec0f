// The solver's step control (solver.h): the proposal from the stable step ([1], dt_scale, dt_max),
// the checks on it, and the steps a coordinator imposes.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/errors.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

namespace {

/// `a` and `b` in seconds with enough digits (7 to 17 significant) to tell them apart, each
/// within a twentieth of their difference: a refused step is often above the allowed one by a few
/// parts in 1e9 (a fixed step planned from the initial stable step, against a stable step that
/// has shrunk since), and 7 digits printed both as the same number.
std::pair<std::string, std::string> apart(double a, double b) {
  int digits = 6;  // after the point: 7 significant
  const double scale = std::max(std::abs(a), std::abs(b));
  const double relative = scale > 0.0 ? std::abs(a - b) / scale : 0.0;
  if (relative > 0.0 && std::isfinite(relative))
    digits = std::clamp(static_cast<int>(std::ceil(-std::log10(relative))) + 1, 6, 16);
  return {fmt::format("{:.{}e}", a, digits), fmt::format("{:.{}e}", b, digits)};
}

}  // namespace

double Solver::step_proposal() const {
  const auto& c = model_.controls;
  double dt = c.dt_scale * dt_stable_;
  if (c.dt_max_s > 0.0) dt = std::min(dt, c.dt_max_s);
  return dt;
}

void Solver::propose_step() {
  const double dt = step_hold_ ? held_step(step_proposal(), dt_) : step_proposal();
  if (!std::isfinite(dt))
    throw ModelError(
        fmt::format("{}: no deformable element gives a stable step (only rigid bodies?); "
                    "set controls.dt_max",
                    domain_));
  if (!(dt > 0.0))
    throw NumericalError(
        fmt::format("{}: stable step {:.3e} s at cycle {}, t = {:.6e} s, set by {}: "
                    "the element collapsed",
                    domain_, dt, cycle_, time_s_, critical_element()));
  if (cycle_ > 0 && dt < 1e-4 * dt_min_)
    throw NumericalError(fmt::format(
        "{}: the stable step fell to {:.3e} s (1e-4 of the smallest step so far, {:.3e} s) at "
        "cycle "
        "{}, t = {:.6e} s, set by {}: an element is collapsing; check its mesh and material",
        domain_, dt, dt_min_, cycle_, time_s_, critical_element()));
  dt_ = dt;
}

std::string Solver::critical_element() const {
  if (global_.binds) {
    const auto& g = global_;
    std::string where = "its refresh";
    if (g.ratio < 1.0 && g.ratio_element >= 0 && g.ratio_part < model_.parts.size()) {
      const auto& p = model_.parts[g.ratio_part];
      where = fmt::format("part '{}' element {} (x {:.3f})", p.name,
                          p.element_id[static_cast<std::size_t>(g.ratio_element)], g.ratio);
    }
    return fmt::format("the mesh's highest frequency (global estimate {:.6e} s, scaled by {})",
                       g.dt_global_s, where);
  }
  if (critical_local_ < 0 && critical_part_ == model_.parts.size()) {
    const auto k = static_cast<std::size_t>(-1 - critical_local_);
    return fmt::format("the penalty springs of contact '{}'", model_.contacts[k].name);
  }
  if (critical_local_ < 0 || critical_part_ >= model_.parts.size()) return "no element";
  const auto& p = model_.parts[critical_part_];
  return fmt::format("part '{}' element {}", p.name,
                     p.element_id[static_cast<std::size_t>(critical_local_)]);
}

void Solver::impose_step(double dt) {
  if (!(dt > 0.0) || dt > dt_ * (1.0 + 1e-9)) {
    const auto& c = model_.controls;
    const auto [imposed, allowed] = apart(dt, dt_);
    throw NumericalError(fmt::format(
        "{}: cycle {}: the coordinator imposed dt = {} s, but the largest step this domain allows "
        "now is {} s (imposed/allowed = 1 + {:.2e}; controls.dt_scale {:g} x its stable step "
        "{:.6e} s{}, set by {}); a coupled step may never exceed a domain's own",
        domain_, cycle_, imposed, allowed, dt / dt_ - 1.0, c.dt_scale, dt_stable_,
        c.dt_max_s > 0.0 ? fmt::format(", capped by controls.dt_max {:.6e} s", c.dt_max_s) : "",
        critical_element()));
  }
  dt_ = dt;
  dt_min_ = std::min(dt_min_, dt_);
}

void Solver::impose_committed_step(double dt) {
  const double cap = model_.controls.dt_max_s;
  const double limit = cap > 0.0 ? std::min(dt_stable_, cap) : dt_stable_;
  if (!(dt > 0.0) || dt > limit * (1.0 + 1e-9)) {
    const auto [committed, allowed] = apart(dt, limit);
    throw NumericalError(fmt::format(
        "{}: cycle {}, t = {:.6e} s: the step {} s committed at the start of the owner step "
        "now exceeds this domain's stable step {} s (set by {}): the mesh stiffened faster "
        "than one coarse step can follow; lower controls.dt_scale or run with fixed steps",
        domain_, cycle_, time_s_, committed, allowed, critical_element()));
  }
  dt_ = dt;
  dt_min_ = std::min(dt_min_, dt_);
}

}  // namespace crashlink::integration
