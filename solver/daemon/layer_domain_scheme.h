#pragma once
// `layer` as one domain's daemon runs it (docs/design.md §2.7 "How to distribute layer"): the
// domain's part of the layer cut (cosim::build_layer_domain) and its cosim::LayerStepper, behind
// coupling::DomainScheme. The Setup fixes its step (or its proposals' limits, variable steps); its
// vectors travel as LayerDisplacement / LayerForce (layer_wire.h), on the partners' lanes when
// there are some; a LayerReport carries its progress and the fine side's interface history rows.
#include <memory>

#include "coupling/domain_scheme.h"
#include "solver/partition/decomposition.h"

namespace crashlink::daemon {

std::unique_ptr<coupling::DomainScheme> make_layer_domain_scheme(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options);

/// `lts`: the same, with the stepper in LayerForm::Lts (docs/multirate.md "lts") on the cut with
/// coupling::kLtsOverlapLayers more layers; fixed or variable steps (no E with variable ones).
std::unique_ptr<coupling::DomainScheme> make_lts_domain_scheme(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options);

}  // namespace crashlink::daemon
