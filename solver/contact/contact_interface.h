#pragma once
// One contact interface (model::Contact) as the integrator sees it: built once, then called every
// cycle at t^{n+1} after the element forces. Penalty with Coulomb friction in one or two passes
// of nodes against segments (contact_pass.h); search in linear time with buckets.
//
// Layouts: x, v, f are interleaved xyz [3n] over all nodes of the domain.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/model/model.h"

namespace crashlink::contact {

struct ContactStep {
  /// The springs' own critical step 2 sqrt(m_eff / k), least over the candidate pairs (no
  /// safety factor; inf if none). The solver combines it with the elements' (solver.cpp).
  double dt_stable_s = 0.0;
  double resultant_N[3] = {0.0, 0.0, 0.0};  ///< sum of the forces on the slave side [N]
  std::int64_t active_pairs = 0;            ///< slave nodes in contact this cycle
  double potential_J = 0.0;  ///< sum of 1/2 k g^2 over the active pairs at t^{n+1} [J]
  /// This interface's contact energy at t^{n+1}: minus the work its forces have done since the
  /// start, trapezoid rule per step (as /history/glstat/contact_energy sums all interfaces).
  /// Frictionless, it equals potential_J up to the step's error; below zero the contact has
  /// created energy [J].
  double energy_J = 0.0;
};

class ContactInterface {
 public:
  /// `mass` [n] lumped nodal masses (for the soft stiffness and the step bound); the model and
  /// the mass array must outlive the interface. Throws ModelError on an empty/invalid definition.
  ContactInterface(const model::Model& m, const model::Contact& c, const double* mass);
  ~ContactInterface();
  ContactInterface(ContactInterface&&) noexcept;
  ContactInterface& operator=(ContactInterface&&) noexcept;

  /// Adds the contact forces at configuration x (t^{n+1}) with mid-step velocities v into f
  /// (f is an external-force accumulator: positive pushes the node). dt = dt^n, the step just
  /// taken (friction's elastic predictor uses v * dt).
  ContactStep compute(const double* x, const double* v, double dt, double* f);
  /// compute() in three steps, so that a solver runs the blocks of all its interfaces on its
  /// threads: begin(), block(b) for every b < block_count() on any thread in any order, then
  /// finish(), with the same result to the bit. Between begin() and finish(), x and v must not
  /// change.
  void begin(const double* x, const double* v, double dt);
  std::size_t block_count() const;
  void block(std::size_t b);
  ContactStep finish(double* f);
  /// The nodes the last finish() (or compute()) pushed, in the order it pushed them, repeated
  /// where pushed more than once: f is untouched at every other node.
  const std::vector<std::int32_t>& applied_nodes() const;

  /// The step the soft stiffness is sized with (contact_pass.cpp pair_stiffness): the domain's
  /// stable step at the start, before any contact. Set once; later calls are ignored (a
  /// restarted run keeps its checkpoint's).
  void set_step_reference(double dt0_s);

  /// Checkpoints: the search state (candidates, travel since the last sort), the friction
  /// history and the contact memory of every slave node, under `prefix`.
  void save_state(core::StateWriter& w, const std::string& prefix) const;
  void restore_state(const core::StateReader& r, const std::string& prefix);

  const std::string& name() const;
  /// Diagnostics: bucket sorts done so far, candidate pairs of the last sort, master segments.
  std::int64_t sort_count() const;
  std::size_t segment_count() const;
  /// Diagnostics: slave-node tests skipped so far by sleeping nodes (docs/contact.md "Search").
  std::int64_t slept_node_cycles() const;
  /// Every node the interface acts on (its passes' nodes and segment nodes), sorted.
  std::vector<std::int32_t> nodes() const;
  /// 1 (node-to-surface, single-surface, or two-pass without slave faces) or 2.
  std::size_t pass_count() const;
  /// The slave nodes tested per cycle, summed over the passes (a two-pass contact counts both
  /// sides): the denominator of the contact cost per slave node-cycle (Solver::cost()).
  std::size_t slave_node_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::contact
