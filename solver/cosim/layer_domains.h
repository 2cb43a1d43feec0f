#pragma once
// The pieces every in-process runner of the `layer` scheme (docs/design.md §2.7, "How to distribute
// layer") shares: one integration::Solver per non-empty domain of partition::decompose(global,
// Layer), its ghost nodes J with their owners, J's natural summed mass and rotary inertia, the
// t = 0 exchange on J and the summed energy account. Used by SplitRunner and LayerNetwork.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "solver/cosim/layer_stepper.h"
#include "solver/integration/energy.h"
#include "solver/integration/solver.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::cosim {

/// A ghost node of one solver and where its owner integrates it.
struct GhostLink {
  std::size_t local = 0;        ///< local index in the ghost's solver
  std::size_t owner = 0;        ///< owner solver index
  std::size_t owner_local = 0;  ///< local index in the owner
};

struct LayerDomains {
  partition::Decomposition dec;
  std::vector<std::unique_ptr<integration::Solver>> solvers;
  std::vector<int> domain_of;                  ///< [solvers] domain index
  std::vector<std::vector<GhostLink>> ghosts;  ///< [solvers][ghosts], Solver::ghost_nodes() order
  std::vector<std::size_t> owner_solver;       ///< [n_global] solver owning the node (or none)
  std::vector<std::size_t> owner_local;        ///< [n_global] its local index there
};

inline constexpr std::size_t kNoSolver = static_cast<std::size_t>(-1);

/// Cuts `global` with the layer scheme and builds the solvers (ghosts, J masses and inertias set,
/// not initialised). `who` prefixes the ModelError messages. `overlap_layers`: the `lts` scheme's
/// further coarse element layers in the finer domain (partition::decompose).
LayerDomains build_layer_domains(const model::Model& global, const char* who,
                                 int overlap_layers = 0);

/// One domain of a layer cut, for a daemon that runs only that domain: its solver (ghosts, J
/// masses and inertias set as in build_layer_domains, not initialised) and its ports (one per
/// interface it takes part in, LayerPort::partner_step left 0: the coordinator's Setup gives it).
/// Throws ModelError naming the domain when `name` is not a non-empty domain of `dec`.
struct LayerDomain {
  int domain_index = -1;  ///< index into dec.domains
  std::unique_ptr<integration::Solver> solver;
  std::vector<LayerPort> ports;
};
LayerDomain build_layer_domain(const partition::Decomposition& dec, const model::Model& global,
                               const std::string& name);

/// The ports of every solver of `d` (LayerDomains::solvers order), partner_step left 0.
std::vector<std::vector<LayerPort>> layer_ports(const LayerDomains& d);

/// After initialize() of every solver: adds the ghost holders' forces on J at t = 0 to the
/// owners' a^0 through Solver::set_acceleration (counted as coupling work over the first step).
void exchange_initial_forces(LayerDomains& d);

/// Sum of the solvers' energy accounts; `reference` carries the running reference over.
integration::EnergyAccount sum_energies(const LayerDomains& d, double reference);

/// [3 n_global] displacement of every global node from its owner [m].
std::vector<double> global_displacement(const LayerDomains& d);

}  // namespace crashlink::cosim
