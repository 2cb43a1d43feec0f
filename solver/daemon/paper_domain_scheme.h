#pragma once
// `paper` as one domain's daemon runs it (docs/design.md §2.6; Bourel 2005 [5]-[11]): every cycle
// a FreeState of the coupled nodes to the coordinator, then the Correction it answers with,
// applied before the cycle begins (paper_port.h), behind coupling::DomainScheme. No lanes, no
// checkpoints; the Setup's summed masses may rebuild the solver ([5]).
#include <memory>

#include "coupling/domain_scheme.h"
#include "solver/partition/decomposition.h"

namespace crashlink::daemon {

std::unique_ptr<coupling::DomainScheme> make_paper_domain_scheme(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options);

}  // namespace crashlink::daemon
