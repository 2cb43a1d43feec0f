#pragma once
// Set-up advice on the contacts of a model: choices that run but give a wrong answer, said before
// the run (docs/scenario-format.md "contacts").
#include <string>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::contact {

/// Median edge length of 4-node faces (4 node indices each; a triangle's repeated node gives a
/// zero edge, skipped) at the initial coordinates [m]; 0 without faces.
double median_edge_m(const model::Model& m, const std::vector<std::int32_t>& faces);

/// One line per contact set up against its own accuracy: a one-pass (node_to_surface) contact
/// whose slave faces are coarser than the master surface by more than kCoarseSlaveRatio lets the
/// master's finer nodes sink between the slave nodes (a one-pass contact checks only the slave
/// nodes; what that costs on two bars: docs/scenario-format.md "contacts",
/// tests/integration/contact_bar_pair_test.cpp). Empty when nothing is to be said.
std::vector<std::string> advice(const model::Model& m);

/// One line per single-surface contact whose parts lie in more than one domain (Model::domains):
/// each domain computes it over its own elements (partition/sub_model.cpp), so parts in different
/// domains never meet. Said before a split or multi run; empty without domains.
std::vector<std::string> domain_advice(const model::Model& m);

/// Slave faces coarser than the master's by this factor draw the advice.
inline constexpr double kCoarseSlaveRatio = 1.5;

}  // namespace crashlink::contact
