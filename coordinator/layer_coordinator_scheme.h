#pragma once
// `layer` as the coordinator runs it (docs/design.md §2.7 "How to distribute layer"): the layer
// cut (layer_cut.h), the fixed steps (split: common, multi: nested) or the first of variable
// ones, the lanes when every daemon offered one (docs/processes.md "Lanes"), the routing of
// LayerDisplacement / LayerForce through the coordinator otherwise (coupling/layer_router.h),
// the interface history rows of the fine sides' LayerReports, and when the coordinator's
// checkpoints (coordinator_checkpoints.h, the coordinator's) may be written, behind
// CoordinatorScheme.
#include <memory>

#include "coordinator/coordinator_scheme.h"
#include "solver/model/model.h"

namespace crashlink::coordinator {

/// `layer`'s rule on a run's configuration: no drift correction to switch off (InputError).
void validate_layer_config(const coupling::CouplingConfig& config);

/// `options` must outlive the scheme.
std::unique_ptr<CoordinatorScheme> make_layer_coordinator_scheme(const model::Model& model,
                                                                 const CoordinatorOptions& options);

/// `lts` (leapfrog local time stepping, docs/multirate.md "lts"): `layer`'s coordinator side on
/// the cut with coupling::kLtsOverlapLayers more layers; its rules: `layer`'s, and fixed steps.
void validate_lts_config(const coupling::CouplingConfig& config);
std::unique_ptr<CoordinatorScheme> make_lts_coordinator_scheme(const model::Model& model,
                                                               const CoordinatorOptions& options);

}  // namespace crashlink::coordinator
