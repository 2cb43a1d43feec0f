#pragma once
// The stability map's contact case (issue #5: "penalty scale factors"; docs/design.md §2.7 "Contact
// across subdomains"): a fine elastic steel hex block, 4 x 4 x 4 elements of dx = 10 mm (domain
// "fine"), dropped at 2 m/s from 1 mm onto a coarse steel slab of 8 x 8 x 2 hexes r dx on a side
// (domain "coarse": parts "coarse" and "coarse_top", one element layer each), its bottom fixed;
// no gravity. Contact: the block's nodes (slave) on the top layer's exterior faces (master) with
// the given penalty scale (LS-DYNA SOFT = 0 stiffness x scale). Under `layer` the slab's top
// element layer moves into the fine domain; under `paper`
// the slab's domain holds copies of the block's nodes. The penalty enters the stable step (the
// solver's own rule), so a scale too stiff for the fixed steps ends with the solver's error.
#include <cstdint>

#include "solver/model/model.h"
#include "studies/free_vibration.h"

namespace crashlink::studies {

model::Model contact_drop_model(double r, double penalty_scale);

/// run_layer_energy / run_paper_energy on contact_drop_model(r, penalty_scale).
FreeVibrationResult run_layer_contact_drop(double r, double penalty_scale, std::int64_t fine_steps);
FreeVibrationResult run_paper_contact_drop(double r, double penalty_scale, std::int64_t fine_steps,
                                           bool drift);

}  // namespace crashlink::studies
