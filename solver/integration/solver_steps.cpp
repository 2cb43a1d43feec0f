// The solver's step control (solver.h): the proposal from the stable step ([1], dt_scale, dt_max),
// the checks on it, and the steps a coordinator imposes.
#include <cmath>

#include "solver/core/errors.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

double Solver::step_proposal() const {
  const auto& c = model_.controls;
  double dt = c.dt_scale * dt_stable_;
  if (c.dt_max_s > 0.0) dt = std::min(dt, c.dt_max_s);
  return dt;
}

void Solver::propose_step() {
  const double dt = step_proposal();
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
  if (!(dt > 0.0) || dt > dt_ * (1.0 + 1e-9))
    throw NumericalError(fmt::format(
        "{}: cycle {}: the coordinator imposed dt = {:.6e} s, but this domain's stable step is "
        "{:.6e} s (set by {}); a coupled step may never exceed a domain's own",
        domain_, cycle_, dt, dt_, critical_element()));
  dt_ = dt;
  dt_min_ = std::min(dt_min_, dt_);
}

void Solver::impose_committed_step(double dt) {
  const double cap = model_.controls.dt_max_s;
  const double limit = cap > 0.0 ? std::min(dt_stable_, cap) : dt_stable_;
  if (!(dt > 0.0) || dt > limit * (1.0 + 1e-9))
    throw NumericalError(fmt::format(
        "{}: cycle {}, t = {:.6e} s: the step {:.6e} s committed at the start of the owner step "
        "now exceeds this domain's stable step {:.6e} s (set by {}): the mesh stiffened faster "
        "than one coarse step can follow; lower controls.dt_scale or run with fixed steps",
        domain_, cycle_, time_s_, dt, limit, critical_element()));
  dt_ = dt;
  dt_min_ = std::min(dt_min_, dt_);
}

}  // namespace crashlink::integration
