#pragma once
// `paper` as the coordinator runs it (docs/design.md §2.6; Bourel 2005 [8]-[11]): the `paper` cut
// (paper_cut.h), the summed masses and roles in the Setups, then every FreeState to a
// PaperExchange (paper_exchange.h) and the Corrections it allows back, its interface rows into
// the history; its guard stops the run as "the coupling went unstable". No checkpoints, no
// restart, no lanes, behind CoordinatorScheme.
#include <memory>

#include "coordinator/coordinator_scheme.h"
#include "solver/model/model.h"

namespace crashlink::coordinator {

/// `paper`'s rule on a run's configuration: no checkpoints, no restart (InputError).
void validate_paper_config(const coupling::CouplingConfig& config);

/// `options` must outlive the scheme.
std::unique_ptr<CoordinatorScheme> make_paper_coordinator_scheme(const model::Model& model,
                                                                 const CoordinatorOptions& options);

}  // namespace crashlink::coordinator
