#pragma once
// What one domain of a `paper` cut (partition::Scheme::Paper; docs/design.md §2.2, §2.5) couples:
// its interface nodes in a fixed order, with their role for the drift correction [11], and the
// pieces of [5] every party computes the same way. Shared by cosim::PaperRunner (both domains in
// one process), the solver daemon (one domain) and the coordinator (every domain's expected
// Register), so that all three list the same nodes in the same order.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/integration/solver.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::cosim {

/// One coupled node of domain d: a link node (present in the two domains whose elements use it)
/// or a contact copy / its original (§3.1 of Bourel 2005).
struct PaperNodeOfDomain {
  std::size_t global = 0;       ///< global node index
  std::size_t local = 0;        ///< index in domain d's sub-model
  std::uint32_t interface = 0;  ///< Decomposition::interfaces index
  int partner = -1;             ///< the other domain (Decomposition::domains index)
  bool reference = false;       ///< d is [11]'s reference side for this node
  bool copy = false;            ///< d holds this node as a copy of another domain's slave node
};

/// Domain d's coupled nodes: every interface that involves d, in Decomposition::interfaces order,
/// each interface's nodes in ascending global index. Throws ModelError when a node belongs to two
/// interfaces (a link node that is also copied for a contact: each node is coupled once), or
/// when a node of an interface is missing from d (an internal error of the cut).
std::vector<PaperNodeOfDomain> paper_nodes(const partition::Decomposition& dec, int d);

/// Translations only: throws ModelError naming the node and both domains when a link node of
/// domain d (`nodes` = paper_nodes(dec, d)) carries rotary inertia in d and in its partner (a
/// shell node shared by shells on both sides) - [8] would be needed on the angular accelerations
/// too, and the Solver has no hook to impose one. A shell node welded to solids (rotations on one
/// side only) is coupled exactly by its translations; copies carry no rotation.
void refuse_rotations_on_both_sides(const partition::Decomposition& dec, int d,
                                    const std::vector<PaperNodeOfDomain>& nodes);

/// Partial lumped masses [n] kg and rotary inertias [n] kg m^2 of a (sub-)model, as
/// Solver::assemble_masses computes them (a contact copy has none): the m^k of [5].
void partial_masses(const model::Model& m, std::vector<double>& mass_kg,
                    std::vector<double>& inertia_kgm2);

/// Kinetic energy of the listed nodes in the Solver's product form, sum of
/// 1/2 M v^{n-1/2} . v^{n+1/2} (after begin_cycle()), M the node's integration mass [J]. The guard
/// of `paper` subtracts it for the reference presences: both presences carry the summed mass.
double product_kinetic_energy(const integration::Solver& s, const std::vector<std::size_t>& nodes);

}  // namespace crashlink::cosim
