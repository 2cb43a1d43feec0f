#pragma once
// Conventional mass scaling at t = 0 (LS-DYNA *CONTROL_TIMESTEP DT2MS < 0 with MS1ST 1): every
// deformable element whose stable step is below the target takes the density that brings its
// step to the target, s_e = (dt_target / dt_e)^2, since dt_e ~ sqrt(rho) (2 / omega_max with
// omega_max^2 ~ 1 / rho: hex8.h, shell_bt.h); the rest keep theirs. The added mass is what the
// answer pays for the step: it is reported, and the run's kinetic energy carries it.
#include <cstddef>
#include <string>

#include "solver/model/model.h"

namespace crashlink::integration {

struct MassScalingReport {
  double target_dt_s = 0.0;         ///< the step every element reaches at least (no safety)
  std::size_t scaled_elements = 0;  ///< elements that got a factor > 1
  std::size_t deformable_elements = 0;
  double mass_kg = 0.0;         ///< the model's mass before [kg]
  double added_mass_kg = 0.0;   ///< what the scaling added [kg]
  double largest_factor = 1.0;  ///< the largest density factor
  std::string largest_element;  ///< "element <id> of part '<name>'"
  /// One line for the user: the target, the elements scaled, the mass added (and its share),
  /// the largest factor and where.
  std::string summary() const;
};

/// Sets Part::element_density_scale on every part with an element below
/// m.controls.mass_scaling_dt_s (nothing if it is 0), from factors 1: a factor the part had is
/// replaced. The steps are those of the model's initial force computation (a throwaway Solver).
/// Throws ModelError for a target at or above the end time (a unit slip) or an element without
/// a finite positive step.
MassScalingReport apply_mass_scaling(model::Model& m);

/// What the model's density factors add (the lumped masses with and without them): for the
/// run's report of a scaled model.
MassScalingReport describe_mass_scaling(const model::Model& m);

}  // namespace crashlink::integration
