#pragma once
// Merging coincident nodes by position: how a part is attached to the parts built before it.
#include <cstddef>

#include "solver/model/model.h"

namespace crashlink::model {

/// Merges every node with index >= first_new (the nodes just appended) into the nearest node with
/// index < first_new within tolerance_m [m] (> 0). Merged nodes are removed, the connectivity of
/// every part is remapped, and the surviving new nodes keep their order and are renumbered with
/// contiguous ids starting at the first new node's id. Nodes are bucketed in a hash grid of cell
/// size tolerance_m, so the cost is O(n) on average (27 neighbour cells per query).
/// Returns the number of nodes merged.
std::size_t merge_coincident_nodes(Model& m, std::size_t first_new, double tolerance_m);

}  // namespace crashlink::model
