#pragma once
// One domain of a `paper` run as its daemon sees it (docs/design.md §2.2-§2.5; Bourel 2005
// [5]-[11]): its coupled nodes (cosim::paper_nodes order, the order of its Register and of every
// FreeState and Correction), their own partial masses m^k, its Solver integrating them with the
// summed mass M ([5]), and the conversions between the Solver and the wire:
//   FreeState: the free accelerations a = f / M of the coupled nodes ([5]), u, v^{n-1/2}, and the
//              energies at the previous instant (with the kinetic energy of the reference
//              presences, which the coordinator's guard counts once);
//   Correction: the corrected accelerations ([8]-[11]) through Solver::set_acceleration (a held
//              dof keeps 0), which counts M (a* - a_free) as coupling work.
// Separate from daemon.cpp so that tests check the conversions without sockets.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "proto/crashlink.pb.h"
#include "solver/cosim/paper_nodes.h"
#include "solver/integration/solver.h"
#include "solver/partition/decomposition.h"

namespace crashlink::daemon {

struct PaperPort {
  const partition::DomainModel* domain = nullptr;
  std::vector<cosim::PaperNodeOfDomain> nodes;  ///< [n] Register order
  std::vector<double> own_mass_kg;              ///< [n] m^k (0 for a copy)
  std::vector<double> summed_mass_kg;           ///< [n] M: the cut's natural sums until the Setup
  std::vector<std::size_t> reference;           ///< local indices of the reference presences
  std::unique_ptr<integration::Solver> solver;  ///< not initialized
};

/// Domain `name` of a Paper decomposition (which must outlive the port). Throws ModelError when
/// the domain is unknown or empty, or a link node carries rotations in both domains (the Solver
/// cannot impose a corrected angular acceleration: cosim::PaperRunner's rule).
PaperPort build_paper_port(const partition::Decomposition& dec, const std::string& name);

/// The Setup's summed masses and roles, checked against this domain's cut (sizes, roles, masses
/// within 1e-12 of the cut's natural sums), kept in port.summed_mass_kg. When they differ in any
/// bit from the ones port.solver was built with, returns a new solver built with them (not
/// initialized) for the caller to swap in; else nullptr. Throws ProtocolError naming
/// the domain and the node.
std::unique_ptr<integration::Solver> use_summed_masses(PaperPort& port, const wire::Setup& setup,
                                                       const std::string& domain);

/// After initialize() or end_cycle_accelerations(): the free state at `time_ticks` into `out`
/// (reused: its arrays keep their capacity). energy: the terms at energy_time_ticks (-1: none
/// yet).
void fill_free_state(const PaperPort& port, std::int64_t time_ticks, std::int64_t stable_step_ticks,
                     const wire::EnergyTerms& energy, std::int64_t energy_time_ticks,
                     wire::Envelope& out);

/// After begin_cycle(): this domain's energy terms at its instant (wire form).
wire::EnergyTerms energy_terms(const PaperPort& port);

/// Applies a Correction's accelerations (sizes and finiteness checked: ProtocolError).
void apply_correction(PaperPort& port, const wire::Correction& c, const std::string& domain);

}  // namespace crashlink::daemon
