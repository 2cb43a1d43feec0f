#pragma once
// The `split` mode of the `layer` scheme (docs/design.md §2.7, "How to distribute layer") in one
// process, at a common step: the global model is cut by partition::decompose(global, Layer)
// (docs/decomposition.md) and every non-empty domain runs its own integration::Solver on its
// sub-model, coupled through the Solver's hooks (solver.h). Every cycle, all domains at the same
// step (the smallest proposal, imposed on all, the mono-scale rule of docs/design.md §2.6):
//
//   begin_cycle() of every domain                      (v^{n+1/2}, energies at t^n; [2])
//   in coarse-to-fine order (every ghost's owner before the ghost's domain):
//     ghosts J <- owner's u^{n+1}; end_cycle_forces()  (u^{n+1}, f(u^{n+1}); [1], [2])
//   for every ghost J: owner.add_coupling_force(J, fine side's net force on J)
//                                                      (the link sum [8] of Bourel 2005: both
//                                                       sides' forces over J's summed mass)
//   end_cycle_accelerations() of every domain          (a^{n+1} = M^{-1} f; [1])
//   dt^{n+1} = min over domains of the proposals, imposed on all.
//
// At a common step this is the single-domain central-difference cycle with the element loop cut
// in pieces, so it reproduces the mono run to round-off (tests/integration/split_mono_test.cpp).
// t = 0: after initialize() the fine sides' forces on J at t = 0 are added to the owners' a^0 the
// same way (via Solver::set_acceleration, whose implied force is counted as coupling work).
//
// Shell J nodes: the same exchange for the rotations: the ghost gets the owner's omega^{n+1/2}
// (set_ghost_angular_velocity), the owner the layer's moment (add_coupling_moment) and J's natural
// summed rotary inertia (set_inertia_override).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/cosim/layer_domains.h"
#include "solver/integration/energy.h"
#include "solver/integration/solver.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::cosim {

class SplitRunner {
 public:
  /// Cuts `global` (which must outlive the runner) with the `layer` scheme and builds one solver
  /// per non-empty domain with its ghost nodes and J masses set. Throws ModelError like decompose.
  explicit SplitRunner(const model::Model& global);
  SplitRunner(const SplitRunner&) = delete;
  SplitRunner& operator=(const SplitRunner&) = delete;

  /// t = 0 in every domain, the t = 0 exchange on J, and the common first step.
  void initialize();
  /// begin_cycle() of every domain (state and energies at t^n complete: sample here).
  void begin_cycle();
  /// The coupled end of the cycle (see the file comment), then the common step dt^{n+1}.
  void end_cycle();
  /// True when every domain has reached the end time (after begin_cycle()).
  bool finished() const;

  double time_s() const;
  std::int64_t cycle() const;
  /// The common step dt^n about to be taken [s].
  double dt_s() const { return dt_; }

  /// [3 n_global] displacement of every global node, taken from its owner domain [m].
  std::vector<double> global_displacement() const;
  /// Sum over the domains of their energy accounts at t^n (after begin_cycle()); the reference of
  /// the balance error is the largest summed energy seen so far. Mass and kinetic energy of J are
  /// counted once (owner only); the coupling work of the domains cancels in the sum.
  const integration::EnergyAccount& energy() const { return energy_; }

  const partition::Decomposition& decomposition() const { return d_.dec; }
  /// Solvers of the non-empty domains, in decomposition order; solver_domain(k) is the index of
  /// solver k's domain in decomposition().domains.
  std::size_t solver_count() const { return d_.solvers.size(); }
  const integration::Solver& solver(std::size_t k) const { return *d_.solvers[k]; }
  int solver_domain(std::size_t k) const { return d_.domain_of[k]; }
  /// The processing order (solver indices), coarse first: every ghost's owner precedes it.
  const std::vector<std::size_t>& order() const { return order_; }

 private:
  void build_order();
  void send_coupling_forces();
  void impose_common_step();

  LayerDomains d_;  // solvers, ghosts J and their owners (layer_domains.h)
  std::vector<std::size_t> order_;
  std::vector<double> u_ghost_;  // scratch [3 * ghosts]
  integration::EnergyAccount energy_;
  double dt_ = 0.0;
};

}  // namespace crashlink::cosim
