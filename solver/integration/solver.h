#pragma once
// One domain's explicit solver: lumped masses, central differences [1]-[2] of Bourel 2005,
// element kernels per part, rigid bodies, boundary conditions, energy account and guard.
//
// A cycle is split in two so that the state at t^n is complete when it is reported:
//   begin_cycle():  v^{n+1/2} = v^{n-1/2} + dt^{n-1/2} a^n, boundary conditions, energies at t^n,
//                   guard.  Here u^n, v^{n-1/2}, v^{n+1/2}, a^n all hold: sample output now.
//   end_cycle():    u^{n+1} = u^n + dt^n v^{n+1/2}, t^{n+1}, element forces f_int(u^{n+1}),
//                   external forces, a^{n+1} = M^{-1}(f_ext - f_int) ([1]), next stable step.
// Run loop: initialize(); for (;;) { begin_cycle(); sample(); if (finished()) break; end_cycle(); }
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "core/state_archive.h"
#include "solver/contact/contact_interface.h"
#include "solver/elements/hex8.h"
#include "solver/elements/kernel_io.h"
#include "solver/elements/shell_bt.h"
#include "solver/integration/element_chunks.h"
#include "solver/integration/energy.h"
#include "solver/integration/global_step.h"
#include "solver/integration/guard.h"
#include "solver/integration/node_set.h"
#include "solver/integration/rigid_body.h"
#include "solver/integration/step_hold.h"
#include "solver/model/model.h"
#include "solver/parallel/thread_team.h"

namespace crashlink::integration {

/// Per-part runtime data: element history and energy totals.
struct PartRuntime {
  std::variant<std::monostate, elements::Hex8State, elements::ShellState>
      state;                    // monostate: rigid
  elements::KernelResult last;  ///< last kernel call (stable step of the part)
  double internal_energy_J = 0.0;
  double hourglass_energy_J = 0.0;
  double damping_energy_J = 0.0;  ///< stiffness-proportional damping work, part of internal
  /// [ne] each element's stable step at the last force computation (no safety factor); filled
  /// only after Solver::record_element_steps(true).
  std::vector<double> element_dt_s;
};

/// A kinematic sample of one probe at t^n.
struct ProbeValue {
  Vec3 displacement_m{};
  Vec3 velocity_m_s{};
  Vec3 acceleration_m_s2{};
};

class Solver {
 public:
  /// The model must outlive the solver. Validates it (ModelError on inconsistency).
  explicit Solver(const model::Model& model, std::string domain_name = "model");
  ~Solver();
  Solver(Solver&&) noexcept;

  /// Before initialize(): the threads that compute this domain's element forces and nodal passes
  /// (1, the default: the calling thread alone). Every result is the same to the bit for every
  /// count: fixed element chunks assembled in one order, fixed node tiles summed in one order
  /// (docs/threads.md).
  void set_threads(int threads);
  /// Before initialize(): store du and dtheta on every tile, as before 2026-11-29, instead of
  /// recomputing them where read on tiles without ghost, rigid, prescribed or wall nodes (the
  /// tests compare the two runs to the bit).
  void store_every_increment(bool on) { store_every_increment_ = on; }
  /// One domain's run (run::run_single_domain) holds its step: propose_step keeps the step in
  /// force while the proposal exceeds it by less than kStepHold (docs/elements.md "Step hold").
  /// Off by default: a coupled domain takes the steps its coordinator imposes.
  void set_step_hold(bool on) { step_hold_ = on; }
  int threads() const { return threads_; }
  /// CPU seconds of the team's worker threads (0 with one thread): what a solver running as a
  /// thread of a bigger process adds to its own thread's clock.
  double team_cpu_seconds() const;

  /// t = 0: masses, rigid bodies, initial velocities, f^0, a^0 and the first stable step.
  void initialize();
  void begin_cycle();
  /// end_cycle() = end_cycle_forces() + end_cycle_accelerations(). A coupled daemon calls the two
  /// halves itself and exchanges interface forces between them (docs/multirate.md "One domain").
  void end_cycle();
  /// u^{n+1} = u^n + dt^n v^{n+1/2} (ghost nodes: their prescribed displacement), t^{n+1}, and
  /// the forces at t^{n+1}: element, contact, external. = end_cycle_positions() +
  /// end_cycle_compute(); a daemon sends its interface displacements between the two halves so
  /// that its force computation overlaps its partners' work (docs/design.md §2.6 "Overlap").
  void end_cycle_forces();
  /// First half of end_cycle_forces(): u^{n+1} ([2]), rigid bodies, t^{n+1}, the F^n halves of
  /// the trapezoid work terms. Ghost nodes are left unknown, their positions and velocities NaN
  /// until end_cycle_compute() applies their motion (set_ghost_displacement), so this half does
  /// not need it.
  void end_cycle_positions();
  /// Optional, between the two halves: the forces of the elements that touch no ghost node
  /// ([0, interior_elements(p)) of every part), which need nothing a partner sends. A `layer`
  /// fine domain computes them while it waits for the ghosts' motion u_J (docs/design.md §2.6
  /// "Overlap"); end_cycle_compute() does it otherwise. The forces are the same either way.
  void end_cycle_interior_forces();
  /// Second half: the ghosts' motion (set_ghost_displacement and set_ghost_angular_velocity
  /// before it), the forces at t^{n+1} and the F^{n+1} halves of the work terms.
  void end_cycle_compute();
  /// Elements [0, interior_elements(p)) of part p touch no ghost node; a multiple of
  /// elements::kElementBatch (the element count when the domain has no ghosts). The
  /// decomposition puts a fine domain's elements that touch J last in each part
  /// (partition::build_domain), so that this is most of the part. After initialize().
  std::size_t interior_elements(std::size_t p) const { return interior_end_[p]; }
  /// a^{n+1} = M^{-1}(f_ext + f_cont + f_coupling - f_int) ([1]) and the next step proposal.
  void end_cycle_accelerations();

  // ---- coupling hooks (solver daemons; single-domain runs use none of them) ----
  /// Before initialize(): [n] summed interface masses in kg (0 keeps the local lumped mass):
  /// the link nodes' M = sum_k m^k of docs/design.md §2.2, or the natural mass of the layer's J
  /// nodes.
  void set_mass_override(std::vector<double> mass_kg);
  /// Before initialize(): read-only ghost nodes whose motion the coupling prescribes (the `layer`
  /// scheme's J nodes on the fine side). Their mass and kinetic energy belong to another domain.
  void set_ghost_nodes(std::vector<std::int32_t> nodes);
  const std::vector<std::int32_t>& ghost_nodes() const { return ghost_list_; }
  /// Before end_cycle_compute(): ghost displacements at t^{n+1}, [3 * ghost count] [m].
  void set_ghost_displacement(const double* u_next);
  /// Before initialize(): [n] summed rotational inertias [kg m^2] (0 keeps the local one): a shell
  /// J node's natural inertia summed over every element of the global model.
  void set_inertia_override(std::vector<double> inertia_kgm2);
  /// Before end_cycle_compute(): ghost angular velocities omega^{n+1/2} [3 * ghost count] [rad/s]
  /// (shell J nodes; optional: without it a ghost keeps its angular velocity).
  void set_ghost_angular_velocity(const double* omega_mid);
  /// Whether the elements on ghost nodes (the rim) compute the artificial bulk viscosity (on by
  /// default). The `lts` coupling's ghosts move on a reflected path whose velocity is the mirror
  /// image in time of the owner step before (cosim::LayerForm): a viscous term driven by it does
  /// work of either sign, and pumped energy into the Hann pulse bar (docs/multirate.md "lts").
  void set_ghost_bulk_viscosity(bool on) { ghost_bulk_viscosity_ = on; }
  /// Before end_cycle_compute(): the J2 returns of the elements on ghost nodes (the rim) this
  /// cycle (elements::StepInfo::trial_history, defer_return). The `lts` coupling defers them at
  /// the substeps between owner instants: plastic flow driven by the reflected path's
  /// back-and-forth ratcheted the full head impact's rim until it blew up (docs/multirate.md
  /// "Plasticity on the rim"). trial_history: the rim's last call deferred.
  void set_rim_returns(bool trial_history, bool defer) {
    rim_trial_history_ = trial_history;
    rim_defer_return_ = defer;
  }
  /// Between the two halves: -m_int of node i at t^{n+1} (its own domain's moment) [N m].
  Vec3 net_moment(std::size_t i) const;
  /// Between the two halves: adds a coupling moment on node i at t^{n+1} [N m].
  void add_coupling_moment(std::size_t i, const Vec3& m);
  /// Between the two halves: f_ext + f_cont - f_int of node i at t^{n+1} (its own domain's
  /// contribution, what the coupling exchanges) [N].
  Vec3 net_force(std::size_t i) const;
  /// Between the two halves: adds a coupling force on node i at t^{n+1} [N] (its work is
  /// counted as coupling work).
  void add_coupling_force(std::size_t i, const Vec3& f);
  /// add_coupling_force(nodes[j], f[3j..3j+2]) then, if m is not null, add_coupling_moment(
  /// nodes[j], m[3j..3j+2]) for every j in order: the same sums, in one call (a `layer` coarse
  /// domain's g_A on J every step).
  void add_coupling_loads(const std::vector<std::size_t>& nodes, const double* f, const double* m);
  /// After end_cycle_accelerations(): replaces a^{n+1} of node i (the `paper` scheme's corrected
  /// acceleration [8]-[11]); the implied force M (a - a_free) is counted as coupling work.
  void set_acceleration(std::size_t i, const Vec3& a);
  /// Between the coupling loads at t^{n+1} (add_coupling_force/moment, all of them) and
  /// end_cycle_accelerations(): what the next cycle will make of `nodes`, computed now from the
  /// forces at hand so that a coarse `layer` daemon can send u_J(t^{n+2}) before its own nodal
  /// passes (cosim::LayerStepper). For each node, exactly the arithmetic of those passes:
  ///   a^{n+1}   = (f_ext + f_cont + f_coup - f_int) / m,  alpha = (m_coup - m_int) / I   [1]
  ///   v^{n+3/2} = v^{n+1/2} + dt^{n+1/2} a^{n+1}, held dofs 0                            [2]
  ///   u^{n+2}   = u^{n+1} + dt_next v^{n+3/2},  dt^{n+1/2} = (dt^n + dt_next) / 2       [2]
  /// into u_next [3 nodes.size()] [m] and omega_mid (omega^{n+3/2}) [3 nodes.size()] [rad/s]
  /// (nullptr: not wanted). Returns false when some node's next values are set otherwise (rigid,
  /// ghost or prescribed node; then nothing is written), when dt_next exceeds the step the
  /// stable step at hand allows (impose_step() would refuse it), or when a value is not finite:
  /// the caller then waits for the passes and their checks.
  bool predict_next_positions(const std::vector<std::size_t>& nodes, double dt_next, double* u_next,
                              double* omega_mid) const;
  /// After end_cycle(): imposes dt^{n+1} (the coordinator's choice). It may not exceed this
  /// domain's own proposal (NumericalError otherwise).
  void impose_step(double dt);
  /// The same for a step committed earlier (a `layer` fine domain with variable steps fixes the
  /// substeps of a whole owner step at its start, cosim::LayerStepper): it may exceed the
  /// proposal at hand, but not the stable step itself (the Courant limit without dt_scale, capped
  /// by dt_max). NumericalError otherwise, naming the critical element.
  void impose_committed_step(double dt);
  /// dt_scale x the stable step at hand, capped by dt_max: what propose_step() checks and sets.
  /// Known once the forces at t^{n+1} are computed (before end_cycle_accelerations()).
  double step_proposal() const;
  /// True when t^n has reached the end time (checked after begin_cycle()).
  bool finished() const { return time_s_ >= model_.controls.end_time_s * (1.0 - 1e-12); }

  // ---- checkpoints (solver_state.cpp, docs/design.md §2.6 "Checkpoints") ----
  /// Writes everything that evolves (nodal vectors, element histories, rigid bodies, contact
  /// history and candidates, prescribed-motion reactions, energies, time, cycle, steps) at a cycle
  /// boundary: after end_cycle_accelerations() / impose_step(), before the next begin_cycle().
  void save_state(core::StateWriter& w) const;
  /// After initialize() of the same model with the same couplings (ghosts, mass overrides):
  /// replaces that state, so that the next cycles are those of the run that saved it, to the bit.
  /// Throws CheckpointError when a record is missing or sized for another model.
  void restore_state(const core::StateReader& r);

  double time_s() const { return time_s_; }
  std::int64_t cycle() const { return cycle_; }
  double dt_s() const { return dt_; }          ///< dt^n, the step about to be taken
  double dt_min_s() const { return dt_min_; }  ///< smallest step taken so far
  /// Smallest element step (before the safety factor) and where it is.
  double dt_stable_s() const { return dt_stable_; }
  std::string critical_element() const;
  /// Energies at t^n: consistent after begin_cycle() (between end_cycle() and the next
  /// begin_cycle() the work terms are already at t^{n+1} while the kinetic energy is not).
  const EnergyAccount& energy() const { return energy_; }
  /// The floor under the guard's reference energy [J] (energy_scale.h), after initialize().
  double guard_floor_J() const { return guard_floor_J_; }
  const model::Model& model() const { return model_; }
  const std::string& domain_name() const { return domain_; }

  // Nodal state, interleaved xyz [3n]. velocity_mid() is v^{n+1/2} after begin_cycle().
  const std::vector<double>& displacement() const { return u_; }
  const std::vector<double>& velocity_mid() const { return v_; }
  const std::vector<double>& acceleration() const { return a_; }
  const std::vector<double>& mass() const { return mass_; }
  const std::vector<double>& inertia() const { return inertia_; }
  /// omega^{n+1/2} after begin_cycle() [3n] [rad/s].
  const std::vector<double>& angular_velocity_mid() const { return omega_; }
  /// v^n = (v^{n-1/2} + v^{n+1/2}) / 2 of node i (after begin_cycle()).
  Vec3 node_velocity(std::size_t i) const;
  ProbeValue probe(const model::Probe& p) const;
  const std::vector<RigidBodyState>& rigid_bodies() const { return bodies_; }
  /// The spot welds that have failed so far (name, time, forces at failure).
  const std::vector<WeldFailure>& weld_failures() const { return weld_failures_; }
  const std::vector<PartRuntime>& parts() const { return parts_; }
  /// The global stable step's state (Controls::global_stable_step; .on false otherwise).
  const GlobalStep& global_step() const { return global_; }
  /// Keep every element's stable step in PartRuntime::element_dt_s (from the next force
  /// computation: call before initialize() for the initial steps). For analysis (`advise`).
  void record_element_steps(bool on) { record_element_steps_ = on; }
  /// Element output of part p (von Mises, eps_p, stress); rigid parts give zeros.
  void element_output(std::size_t p, const elements::ElementOutput& out) const;
  /// Total mass of the model [kg] (nodes + rigid bodies).
  double total_mass_kg() const;
  /// Contact interfaces (model.contacts order) and their last step (resultant force on the slave
  /// side at t^n).
  const std::vector<contact::ContactStep>& contact_steps() const { return contact_steps_; }
  /// What the contacts have cost this process so far (not kept in checkpoints): CPU seconds of
  /// their search and forces, and the slave nodes they tested summed over the evaluations
  /// (initialize() and each cycle; the scale benchmark's ns per slave node-cycle).
  struct ContactCost {
    double seconds = 0.0;
    std::int64_t node_cycles = 0;
  };
  const ContactCost& contact_cost() const { return contact_cost_; }
  /// What the element kernels have cost this process so far (not kept in checkpoints), sampled
  /// on the last cycle of every kKernelSampleCycles (not cycle 0, whose caches are cold) to keep
  /// the clock's price (~0.4 us a read here) off the others: the cycles sampled, thread CPU
  /// seconds in the kernels of those cycles summed over the threads, and the element-cycles they
  /// computed, per model::ElementKind (the scale benchmark's ns per hex- and per shell-cycle).
  /// The global step's probes are not in them: `global_step_seconds` is the CPU of its
  /// refreshes after set-up, every one: the calling thread's and the workers' probe kernels (the
  /// workers' part of its node loops is not counted).
  struct KernelCost {
    std::int64_t sampled_cycles = 0;
    std::array<double, 2> seconds{};               ///< [kind] CPU [s]
    std::array<std::int64_t, 2> element_cycles{};  ///< [kind]
    double global_step_seconds = 0.0;              ///< CPU [s]
  };
  static constexpr std::int64_t kKernelSampleCycles = 16;
  KernelCost kernel_cost() const;
  /// Rigid wall k (model.rigid_walls[k]): its force on the nodes it stops at this cycle, summed
  /// over them [N] (along its normal), and the work it has done on them since t = 0 [J] (< 0:
  /// kinetic energy it took).
  Vec3 wall_force_N(std::size_t k) const { return walls_[k].force_N; }
  double wall_work_J(std::size_t k) const { return walls_[k].work_J; }
  /// A moving wall's travel along its normal since t = 0 at t^n [m] and its velocity over the
  /// step about to be taken [m/s] (0 and 0 for a fixed wall).
  double wall_travel_m(std::size_t k) const { return walls_[k].travel_m; }
  double wall_velocity_m_s(std::size_t k) const { return walls_[k].velocity_m_s; }

 private:
  void assemble_masses();
  void build_rigid_bodies();
  /// The turning nodes of every rigid body (RigidBodyState::turning) take its angular velocity.
  void turn_rigid_nodes();
  /// Spot welds (model::RigidBody::Failure) whose force meets their criterion at t^n let go of
  /// their nodes (release_body), recorded in weld_failures_.
  void check_spot_welds();
  /// Body k's nodes move on their own from now (with `accelerate`, their accelerations at t^n
  /// from their loads; a restored checkpoint holds them).
  void release_body(std::size_t k, bool accelerate = true);
  void apply_initial_velocities();
  /// Which elements compute_forces() takes: all of them; the interior ones (f_int, m_int
  /// cleared first); the rest (added).
  enum class ElementSpan { All, Interior, Rim };
  // f_int, m_int at the current configuration
  void compute_forces(double dt, ElementSpan span = ElementSpan::All);
  /// end_cycle_compute's first step: the ghosts' displacement, velocity and rotation increment
  /// over the step from the coupling's u^{n+1} and omega^{n+1/2}, and the work terms that
  /// end_cycle_positions() summed with their provisional increments, corrected.
  void apply_ghost_motion();
  void compute_external_forces(double t);
  void compute_contact_forces(double dt);  // f_cont at the current configuration
  void set_contact_step_references();      // the soft springs' step (needs element_dt_s)
  void compute_accelerations();
  double kinetic_energy() const;
  /// sum + m v^{n-1/2} . v^{n+1/2} + I omega^{n-1/2} . omega^{n+1/2} of nodes [i0, i1) (within
  /// the tile of i0), in node order, over the nodes the kinetic energy counts (not rigid, not
  /// ghosts).
  double kinetic_sum(std::size_t i0, std::size_t i1, double sum) const;
  /// The same over given arrays: v, w at n+1/2 and vp, wp at n-1/2 (velocity_pass's buffers
  /// before their swap).
  double kinetic_sum(const double* v, const double* vp, const double* w, const double* wp,
                     std::size_t i0, std::size_t i1, double sum) const;
  /// 1/2 node_sum plus the rigid bodies' kinetic energy.
  double kinetic_energy_from(double node_sum) const;
  /// begin_cycle's velocity update, held dofs and nodal kinetic-energy sum in one pass (no
  /// prescribed velocities, not the first cycle); returns the sum.
  double velocity_pass(double dt_mid);
  double ghost_reaction_work(double weight) const;  // weight * sum_g R_g . du_g
  /// Reaction of a massless prescribed (ghost) node at dof k of [3n]: R = f_int - f_ext - f_cont -
  /// f_coup [N]; its moment m_int - m_coup [N m].
  double ghost_reaction(std::size_t k) const {
    return f_int_[k] - f_ext_[k] - f_cont_[k] - f_coup_[k];
  }
  double ghost_reaction_moment(std::size_t k) const { return m_int_[k] - m_coup_[k]; }
  /// Dot products of the F^n halves of the step's work (energy.h): f_ext, f_cont, f_coup with
  /// du and m_coup with dtheta.
  struct StepWork {
    double external = 0.0, contact = 0.0, coupling = 0.0, coupling_moment = 0.0;
  };
  /// u^{n+1} = u^n + dt v^{n+1/2} ([2]), du, dtheta, and on the tiles without rigid nodes x^{n+1}
  /// and the tiles' F^n halves of the external work (tile_sum_).
  void advance_positions(double dt);
  /// After the bodies moved: x = x0 + u on the tiles with rigid nodes (advance_positions did
  /// the others), the StepWork sums, f_coup and m_coup cleared.
  StepWork positions_and_work();
  void propose_step();
  GuardContext guard_context() const;
  /// The one list of evolving members behind save_state / restore_state (solver_state.cpp);
  /// Self is const Solver when saving, Solver when loading.
  template <class Visitor, class Self>
  static void visit_state(Visitor& v, Self& self);

  const model::Model& model_;
  std::string domain_;
  std::size_t n_ = 0;

  std::vector<double> mass_, inv_mass_;             // [n] kg, 1/kg (0: rigid or massless)
  std::vector<double> inertia_, inv_inertia_;       // [n] kg m^2 (shell nodes)
  std::vector<double> x_;                           // [3n] current coordinates
  std::vector<double> u_, v_, v_prev_, a_;          // [3n] u^n, v^{n+1/2}, v^{n-1/2}, a^n
  std::vector<double> omega_, omega_prev_, alpha_;  // [3n] rotational dofs
  std::vector<double> f_int_, f_ext_, m_int_;       // [3n]
  std::vector<double> f_cont_;                      // [3n] contact forces (push on the node)
  std::vector<double> f_coup_;                      // [3n] coupling forces at t^n
  std::vector<double> mass_override_;               // [n] or empty
  std::vector<double> inertia_override_;            // [n] or empty
  std::vector<double> m_coup_;                      // [3n] coupling moments
  std::vector<double> dtheta_;                      // [3n] dt^n omega^{n+1/2} (dtheta_at)
  std::vector<double> ghost_omega_;                 // [3 * ghosts]
  bool ghost_omega_set_ = false;
  std::vector<std::uint8_t> ghost_;  // [n] 1: ghost node
  std::vector<std::uint8_t>
      prescribed_node_;  // [n] 1: some dof of the node has a prescribed velocity
  std::vector<std::int32_t> ghost_list_;
  std::vector<double> ghost_target_;  // [3 * ghosts] u^{n+1} of the ghosts
  bool ghost_target_set_ = false;
  std::vector<double> du_;                // [3n] u^n - u^{n-1}, on increment_tile_ (du_at)
  std::vector<std::uint8_t> rigid_node_;  // [n] 1 if the node follows a rigid body
  std::vector<PartRuntime> parts_;
  std::vector<RigidBodyState> bodies_;
  std::vector<int> body_of_node_;           ///< [n] the rigid body a node follows, -1: none
  std::vector<WeldFailure> weld_failures_;  ///< spot welds that let go, in order
  std::vector<contact::ContactInterface> contacts_;
  std::vector<contact::ContactStep> contact_steps_;
  std::vector<std::size_t> contact_block_end_;  ///< [contacts] one past each one's last block
  std::vector<double> contact_worker_cpu_;      ///< [threads] a cycle's contact CPU per worker [s]
  ContactCost contact_cost_;
  /// [threads][kind, probes]: sampled kernel CPU and the global step's probes' CPU [s]
  std::vector<std::array<double, 3>> kernel_worker_cpu_;
  std::array<std::int64_t, 2> kernel_element_cycles_{};  ///< [kind] of the sampled cycles
  std::int64_t kernel_sampled_cycles_ = 0;
  std::int64_t kernel_last_sampled_ = -1;  ///< the cycle sampled last
  double global_step_cpu_s_ = 0.0;         ///< the calling thread's CPU in the refreshes [s]

  // prescribed dofs: (dof index into [3n] or rotational [3n] + 3n offset), curve, reaction R^n
  struct PrescribedDof {
    std::size_t index;
    bool rotational;
    const model::Curve* curve;
    double reaction_prev = 0.0;
  };
  std::vector<PrescribedDof> prescribed_;

  /// A rigid body's held or prescribed dof (model::RigidBody::fixed,
  /// model::PrescribedVelocity::rigid_body): its centre's velocity along global axis dof (0..2)
  /// or its angular velocity about it (3..5); curve null: held at 0. Reaction R^n [N or N m].
  struct BodyMotion {
    std::size_t body;
    int dof;
    const model::Curve* curve;
    double reaction_prev = 0.0;
  };
  std::vector<BodyMotion> body_motions_;
  std::vector<std::uint8_t> body_held_;  ///< [bodies] 1: some dof in body_motions_
  /// The held and prescribed dofs of body k at t^n + dt/2 over its momentum update of dt_mid,
  /// and the work of their reactions (trapezoid rule, as a node's prescribed velocity).
  void constrain_rigid_body(std::size_t k, double dt_mid);
  /// body_motions_ from the model (grouped by body), their values at t = 0 set on the bodies.
  void build_body_motions();
  /// update_rigid_momenta, then the held and prescribed dofs, for every body that holds.
  void update_rigid_bodies(double dt_mid);

  /// Rigid walls (model::RigidWall): each wall's reaction R^n at its nodes [3 per node, N], for
  /// the trapezoid rule of its work.
  struct WallRuntime {
    const model::RigidWall* wall = nullptr;
    std::vector<double> reaction_prev;
    Vec3 force_N{};             ///< sum of the reactions of the last application [N]
    double work_J = 0.0;        ///< its work since t = 0 (trapezoid rule) [J]
    double travel_m = 0.0;      ///< a moving wall's displacement along its normal at t^n [m]
    double velocity_m_s = 0.0;  ///< its velocity over [t^n, t^{n+1}] [m/s]
    std::vector<double> gap;    ///< [4 per node] scratch: gap d [m] (NaN: free) and normal
  };
  void wall_gaps(WallRuntime& rw) const;
  std::vector<WallRuntime> walls_;
  void apply_rigid_walls(double dt_pair);

  EnergyAccount energy_;
  /// The guard's floor under energy_.reference_J [J]: kGuardFloorFraction x the model's energy
  /// scale (Controls::model_energy_scale_J) when the decomposition set it, else this solver's own
  /// (energy_scale.h); set by initialize(), constant.
  double guard_floor_J_ = 0.0;
  double time_s_ = 0.0;
  std::int64_t cycle_ = 0;
  double dt_ = 0.0, dt_prev_ = 0.0, dt_min_ = 0.0, dt_stable_ = 0.0;
  bool step_hold_ = false;  ///< set_step_hold
  bool record_element_steps_ = false;
  std::size_t critical_part_ = 0;
  std::int64_t critical_local_ = -1;
  bool begun_ = false;
  bool positions_done_ = false;  // end_cycle_positions() done, end_cycle_compute() not yet
  bool interior_done_ = false;   // end_cycle_interior_forces() done, end_cycle_compute() not yet
  std::vector<std::size_t> interior_end_;  // [parts] interior_elements()
  // ---- threads (solver_threads.cpp, docs/threads.md) ----
  /// Nodes per tile: the nodal passes' unit, and their sums' (one partial sum per tile, added in
  /// tile order). Each thread's node range is whole tiles.
  static constexpr std::size_t kNodeTile = 256;
  int threads_ = 1;
  std::unique_ptr<parallel::ThreadTeam> team_;  // threads_ > 1
  ElementChunks chunks_;
  std::vector<elements::KernelResult> chunk_results_;  // [chunks of the larger span]
  std::vector<std::size_t> chunk_cut_[2];              // [threads + 1]: thread t's chunks of span s
  std::vector<std::size_t> node_cut_;  // [threads + 1]: thread t's nodes (whole tiles)
  std::vector<double> tile_sum_;       // [tiles] partial sums
  // [tiles] 1: the tile holds a node of a rigid body (built before the threads; one let go by a
  // failed spot weld stays marked): its positions wait for the bodies' motion (end_cycle_positions)
  std::vector<std::uint8_t> rigid_tile_;
  bool any_rigid_tile_ = false;
  // [tiles] 1: the tile holds a node with a held dof (model_.fixed, fixed for the run): the
  // others skip zero_held's scan (1 % of the 2.5 mm scale run's samples, perf, 2026-11-29).
  std::vector<std::uint8_t> held_tile_;
  // [tiles] 1: no rigid or ghost node on the tile (kinetic_sum skips its tests; a node let go by a
  // spot weld was rigid at set-up, so its tile is not plain).
  std::vector<std::uint8_t> plain_tile_;
  /// zero_held over the held tiles of nodes [i0, i1) (whole tiles, or a tile's nodes).
  void zero_held_tiles(double* t, double* r, std::size_t i0, std::size_t i1) const;
  // [tiles] 1: du_ and dtheta_ are stored on the tile, which holds a ghost, rigid, prescribed or
  // wall node (there an increment is not dt v, or is read in the next cycle once v has moved).
  // Elsewhere the displacement pass does not store them: du = dt v and dtheta = dt omega where
  // they are read (du_at, dtheta_at), 48 B per node-cycle fewer (docs/benchmarks.md "The nodal
  // passes' floor").
  std::vector<std::uint8_t> increment_tile_;
  bool store_every_increment_ = false;  // store_every_increment()
  double dt_increment_s_ = 0.0;         // dt^n of the last displacement update [s]
  bool increments_everywhere_ = true;   // du_, dtheta_ hold every dof (start, restore)
  bool velocity_moved_ = false;  // v, omega updated since then: it is in v_prev_, omega_prev_
  bool stored_increment(std::size_t node) const {
    return increments_everywhere_ || increment_tile_.empty() || increment_tile_[node / kNodeTile];
  }
  /// u^{n+1} - u^n of dof k (the last displacement update's): stored, or dt^n v^{n+1/2} with the
  /// same rounding as the pass that did not store it.
  double du_at(std::size_t k) const {
    if (stored_increment(k / 3)) return du_[k];
    return dt_increment_s_ * (velocity_moved_ ? v_prev_[k] : v_[k]);
  }
  /// sum over the nodes' dofs of f . du, in their order (sparse_dot, du where it is read).
  double increment_dot(const std::vector<std::int32_t>& nodes, const double* f) const {
    return sparse_dot(nodes, f, [this](std::size_t k) { return du_at(k); });
  }
  /// f_ext . du over the nodes [i0, i1) of one tile, in index order (dot_range's sum).
  double external_increment_work(std::size_t i0, std::size_t i1) const;
  /// advance_positions on tile b (dofs [k0, k1)) without a rigid node; returns its F^n half of the
  /// external work.
  double displacement_tile(std::size_t b, std::size_t k0, std::size_t k1, double dt);
  /// dt^n omega^{n+1/2} of dof k, alike.
  double dtheta_at(std::size_t k) const {
    if (stored_increment(k / 3)) return dtheta_[k];
    return dt_increment_s_ * (velocity_moved_ ? omega_prev_[k] : omega_[k]);
  }
  // [tiles] 0: no node of the tile can turn (hexes' nodes only: no inertia, no initial spin, no
  // rigid, ghost or prescribed rotation): omega, omega_prev, dtheta and m_int stay the zeros
  // initialize() made, alpha too but at coupled nodes (coupling_pass: a moment times the zero
  // 1/I), and the nodal passes leave them out there (memory-bound). Empty before
  // set_up_threads(): every tile turns.
  std::vector<std::uint8_t> turning_tile_;
  bool turning(std::size_t first_node) const {
    return turning_tile_.empty() || turning_tile_[first_node / kNodeTile];
  }
  /// initialize(): the chunks, the team, the cuts (after interior_end_), the rigid and turning
  /// tiles (after the bodies, ghosts, prescribed dofs and initial velocities).
  void set_up_threads();
  void set_up_turning_tiles();
  std::size_t tiles() const { return (n_ + kNodeTile - 1) / kNodeTile; }
  /// f(i0, i1) over every thread's node range, at once.
  template <class F>
  void on_node_ranges(F&& f) {
    if (!team_) {
      f(std::size_t{0}, n_);
      return;
    }
    team_->on_each_thread([&](int t) {
      const auto k = static_cast<std::size_t>(t);
      f(node_cut_[k], node_cut_[k + 1]);
    });
  }
  /// f(i0, i1) -> the sum over tile [i0, i1), for every tile (each thread its own); the tiles'
  /// sums added in tile order.
  template <class F>
  double sum_over_tiles(F&& f) {
    double* sums = tile_sum_.data();
    on_node_ranges([&](std::size_t i0, std::size_t i1) {
      for (std::size_t b = i0; b < i1; b += kNodeTile)
        sums[b / kNodeTile] = f(b, std::min(i1, b + kNodeTile));
    });
    double s = 0.0;
    for (std::size_t t = 0; t < tiles(); ++t) s += sums[t];
    return s;
  }
  /// Part p's kernel over elements [first, end) with the scatter plan (null: into the nodes);
  /// probe: on the global step's zero-stress histories and rates (global_), no bulk viscosity.
  /// rate_terms false: no bulk viscosity (the rim with set_ghost_bulk_viscosity(false)).
  /// rim: the rim's J2 returns as set_rim_returns says.
  elements::KernelResult run_kernel(std::size_t p, double dt, std::size_t first, std::size_t end,
                                    const std::int32_t* scatter, bool probe = false,
                                    bool rate_terms = true, bool rim = false);
  /// The chunks of span s (0 interior, 1 rim) on the team, their shared nodes' slots replayed
  /// into f and m; chunk_results_ holds each chunk's result for the caller to fold in order.
  void run_span(int s, double dt, bool probe, double* f, double* m);
  // ---- global stable step (solver_global_step.cpp, Controls::global_stable_step) ----
  GlobalStep global_;
  bool ghost_bulk_viscosity_ = true;                           ///< set_ghost_bulk_viscosity
  bool rim_trial_history_ = false, rim_defer_return_ = false;  ///< set_rim_returns
  /// initialize(): the probe's arrays and histories, the first estimate.
  void set_up_global_step();
  /// A new estimate of omega_max^2 by `runs` Lanczos runs (a full estimate: its own count), and
  /// the element steps it goes with.
  void refresh_global_step(int runs);
  /// out = M^-1/2 K M^-1/2 z over [6n] (translations, then rotations), K at the current x.
  void global_product(const double* z, double* out);
  /// After the element forces of a cycle: refresh when due, then dt_stable_ = max(dt_stable_,
  /// dt_global x min(1, ratio)).
  void apply_global_step();
  /// min over elements [first, end) of part p of element_dt_s / its step at the last refresh,
  /// and its element (the first on a tie).
  double element_ratio(std::size_t p, std::size_t first, std::size_t end,
                       std::int64_t& where) const;
  /// A kernel call's energies and stable step into part p's and the domain's.
  void add_kernel_result(std::size_t p, const elements::KernelResult& r);
  void prepare_element_steps(std::size_t p);
  // Within a cycle, for apply_ghost_motion(): the ghosts' u^n and their reaction at t^n,
  // R = f_int - f_ext - f_cont - f_coup and m_int - m_coup [3 * ghosts] (the element forces
  // at t^n are gone once the interior ones at t^{n+1} are computed).
  std::vector<double> ghost_u_prev_, ghost_reaction_, ghost_reaction_moment_;
  // Arrays known to hold zeros, not read by the nodal passes (they are memory-bound):
  bool external_loads_ = false;  // gravity or loads: f_ext may be non-zero
  // The nodes whose f_coup / m_coup were written since they were last cleared, and those the
  // contacts pushed in the last compute_contact_forces (in the order they first pushed them:
  // contact by contact, each in its record's order, which no thread count changes): f_coup,
  // m_coup and f_cont are zero elsewhere, so the passes over all nodes leave them out and treat
  // these few apart.
  NodeSet coupled_, contact_nodes_;
  void mark_coupled(std::size_t i) { coupled_.insert(i); }
  /// Contact k's pushed nodes into contact_nodes_ (after its finish(), or restore_state()).
  void add_contact_nodes(std::size_t k) {
    for (const auto node : contacts_[k].applied_nodes())
      contact_nodes_.insert(static_cast<std::size_t>(node));
  }
  /// After f_coup and m_coup were restored from a checkpoint: the nodes that carry them.
  void rebuild_coupled_nodes();
  /// The load that drives node dof k: f_ext + f_cont + f_coup [N] ([1]).
  double driving_load(std::size_t k) const { return f_ext_[k] + f_cont_[k] + f_coup_[k]; }
};

}  // namespace crashlink::integration
