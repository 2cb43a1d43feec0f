#pragma once
// Every domain of a `layer` cut in one process and one thread: one LayerStepper per non-empty
// domain (layer_stepper.h), fixed nested steps (coupling/nested_steps.h), messages routed in
// memory, the earliest domain first (docs/design.md §2.6: the earliest pending state is always
// answerable, so this never deadlocks). It is the reference the daemons must reproduce to
// round-off (they run the same steppers, only the messages travel over ZeroMQ), and the way
// tests and sweeps run `split` and `multi` without processes.
//
//   LayerNetwork net(global, {});  // multi; split: options.run.common_step = true
//   net.initialize();
//   net.run([&](std::size_t k) { ... net.solver(k) sampled at its instant ... });
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "coupling/coupling_config.h"
#include "coupling/nested_steps.h"
#include "coupling/ticks.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

struct LayerNetworkOptions {
  /// How the domains couple: the configuration a run over processes has
  /// (coupling/coupling_config.h), of which the network reads common_step (split: every domain at
  /// the smallest step; multi by default here), variable_steps and ticks_per_second. Every domain
  /// follows its own step proposal with variable_steps (layer_stepper.h "Steps"; multi: the
  /// leaders take step_safety of theirs, LayerStepper::set_proposal_limits; split: all the least
  /// proposal of all at every instant); proposal_s must then stay empty and plan() is not used.
  /// scheme must be "layer" or "lts" (ModelError otherwise; lts: fixed steps, LayerForm::Lts on
  /// every stepper, the cut with overlap_layers); checkpoints are the caller's
  /// (save_state/restore_state), lanes and restart the processes' (not read).
  coupling::CouplingConfig run{.scheme = "layer", .common_step = false};
  /// Margin on the initial stable steps (they shrink as the mesh deforms and bulk viscosity acts;
  /// a fixed step above a later proposal makes Solver::impose_step throw).
  double step_safety = 1.0;
  /// [solvers] optional proposals in seconds replacing the solvers' own (each still capped by
  /// the solver's stable step): how tests impose a ratio. Empty: the solvers' initial steps.
  std::vector<double> proposal_s;
  /// lts: the coarse element layers moved into the finer domain beyond the first
  /// (partition::decompose). The plain leapfrog LTS has unstable step bands without one
  /// (coupling-study/lts/README.md); 0 (the layer cut) is for tests that compare with `layer`.
  int overlap_layers = coupling::kLtsOverlapLayers;
};

class LayerNetwork {
 public:
  /// Cuts `global` (which must outlive the network) with the layer scheme.
  explicit LayerNetwork(const model::Model& global, LayerNetworkOptions options = {});
  LayerNetwork(const LayerNetwork&) = delete;
  LayerNetwork& operator=(const LayerNetwork&) = delete;

  /// Solvers initialised, steps planned, steppers initialised, the t = 0 forces exchanged.
  void initialize();
  /// Checkpoints (docs/design.md §2.6), once run(..., until) has returned false with every domain
  /// paused at one instant (none finished: check stepper(k).time() and at_cycle_boundary()):
  /// domain k's solver and stepper (Solver / LayerStepper::save_state).
  void save_state(std::size_t k, core::StateWriter& w) const;
  /// Instead of initialize(): each domain k resumes from the state file paths[k] (save_state's,
  /// StateWriter::save). Throws CheckpointError for a file of another model or run, ModelError
  /// when paths has not one file per domain.
  void restore(const std::vector<std::string>& paths);
  /// Advances every domain until it has finished or reached `until` ticks (each stops at the
  /// start of its first cycle at or after `until`). on_sample(k) after every begin_cycle() of
  /// solver k. Returns true when every domain has finished. A domain whose partner needs one more
  /// message to reach `until` takes the cycles that send it: under lts a fine domain sends
  /// Fbar(T) only at T + (p - 1) h, so it stops there, past `until` (the domains are then at
  /// different instants, in a tree up to about two coarse steps apart; a daemon instead writes
  /// its checkpoint at T and goes on). Only a paused domain that a waiting one waits on takes
  /// such cycles, so a chain stops too (LtsNetwork.ThreeDomainChainPausesAndRestoresToTheBit,
  /// TreesPausedAnywhereRestoreToTheBit).
  bool run(const std::function<void(std::size_t)>& on_sample = {},
           Tick until = std::numeric_limits<Tick>::max());

  std::size_t size() const { return d_.solvers.size(); }
  const integration::Solver& solver(std::size_t k) const { return *d_.solvers[k]; }
  const LayerStepper& stepper(std::size_t k) const { return *steppers_[k]; }
  const coupling::StepPlan& plan() const { return plan_; }  ///< [solvers] order
  const LayerDomains& domains() const { return d_; }
  const partition::Decomposition& decomposition() const { return d_.dec; }
  double seconds(Tick n) const {
    return static_cast<double>(n) / static_cast<double>(options_.run.ticks_per_second);
  }
  /// Sum of the energy accounts (each at its domain's current instant).
  integration::EnergyAccount energy() const { return sum_energies(d_, 0.0); }
  /// [3 n_global] displacement of every global node from its owner [m].
  std::vector<double> global_displacement() const { return cosim::global_displacement(d_); }
  /// lts: the sum of the domains' shares of the conserved energy E^{k-1/2} (LtsEnergy), valid when
  /// every domain is at the same multiple of plan().base, from the third on (NaN otherwise).
  double lts_energy_J() const;
  /// Messages routed so far (both kinds).
  std::int64_t messages() const { return messages_; }

 private:
  void route(std::size_t from);
  void build_steppers();  ///< initialize() up to the steppers' own initialize()

  LayerNetworkOptions options_;
  LayerDomains d_;
  std::vector<std::unique_ptr<LayerStepper>> steppers_;
  std::vector<std::size_t> fine_of_, coarse_of_;  ///< [interfaces] solver index of each side
  coupling::StepPlan plan_;
  std::int64_t messages_ = 0;
};

}  // namespace crashlink::cosim
