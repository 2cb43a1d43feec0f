#pragma once
// One domain's side of the `layer` scheme (docs/design.md §2.7 "How to distribute layer"), for any
// number of interfaces and any nested steps, written as a state machine that never blocks: it
// runs until it needs a message from a partner and says which. The same object drives a domain
// in the in-process LayerNetwork (layer_network.h) and in a crashlink-solver daemon (the daemon
// blocks on its socket when the stepper waits).
//
// Source: Bourel, Combescure, Di Valentin 2005, [8] (LayerPort). The two sides of an interface:
// LayerPort ("Ports"); the cycle and the u_J sent ahead: LayerStepper ("Cycle"); how steps are
// chosen: LayerSteps ("Steps", "Variable common"). Time is an integer count of ticks
// (coupling/ticks.h). How it runs and what is measured: docs/multirate.md.
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/state_archive.h"
#include "coupling/layer_work.h"
#include "coupling/ticks.h"
#include "solver/cosim/lts_energy.h"
#include "solver/integration/solver.h"

namespace crashlink::cosim {

using coupling::Tick;

/// Ports. Each interface is seen from one domain as a LayerPort:
///   coarse side (fine_side = false): this domain owns J and integrates it at its own step H with
///     a_J = (g_B + g_A) / M_J ([8] of Bourel 2005, M_J the natural summed mass); it sends
///     u_J(T+H) (and the rotation rate omega_J^{T+H/2} of shell nodes) as soon as g_A(T) is
///     applied (predicted; after its positions at T+H at the first step or for rigid or prescribed
///     J), computes its own forces at T+H, then needs the fine side's layer force g_A(T+H) (and
///     moment) before its accelerations at T+H.
///   fine side (fine_side = true): this domain holds J as read-only ghosts moving linearly in time
///     between the owner's positions u_J(T) and u_J(T+H) (rotation rate constant over [T, T+H]);
///     its step h divides H (nested_steps.h), so it lands on every T; at each owner instant it
///     sends the layer's force and moment on J.
/// `local` lists the J nodes in Interface::j_nodes_global order, as every LayerMessage vector
/// does.
struct LayerPort {
  std::uint32_t index = 0;           ///< interface index (Decomposition::interfaces)
  bool fine_side = false;            ///< true: J are ghosts here; false: this domain owns J
  std::string partner;               ///< the other domain's name (messages)
  Tick partner_step = 0;             ///< the owner's step H (fine side only; fixed steps)
  std::vector<std::size_t> local;    ///< [n_J] local solver index of each J node
  std::size_t partner_elements = 0;  ///< the partner's element count (variable steps: its cost)
};

/// A partner's messages do not fit this domain's steps (instants that disagree, a force for
/// another instant): the partner's fault, which a daemon reports as a protocol error naming it.
class LayerPartnerError : public ModelError {
 public:
  using ModelError::ModelError;
};

/// Steps: how a LayerStepper's steps are chosen.
/// Fixed: every domain at the step the coordinator planned for the whole run
/// (coupling/nested_steps.h).
/// Variable (docs/design.md §2.1, [2] with variable steps; every domain follows its stable step as
/// the mesh deforms, as a mono run does):
///   - every domain has at most one coarser partner (its fine ports all name one domain);
///   - a domain without one (a leader) chooses its next step at each of its instants t, once the
///     holders' g_A(t) are in: each g_A carries its sender's step proposal p_k at t (rule:
///     LayerStepper::choose_step);
///   - a domain with one (a follower) learns the owner step [T, T + H] from the time of u_J(T + H)
///     before its first cycle in it, and commits n = ceil(H / p) substeps of H / n (whole ticks,
///     the last ones a tick longer when n does not divide H; LayerStepper::next_substep), p the
///     proposal it sent with g_A(T). The later substeps may not exceed the stable step itself
///     (Solver::impose_committed_step).
///   - a follower's own holders see its substeps as its steps.
/// Variable common (`split`, VariableCommon): one step for all, as a mono run takes it
/// (docs/design.md §2.1: the smallest proposal of all at every instant). Every g_A(t) carries the
/// least proposal of its sender's whole subtree (a domain that holds ghosts and has holders of its
/// own sends its g_A(t) only once its holders' g_A(t) are in); the leader takes H = the least of
/// its own and its holders' (no step safety, no hysteresis, no limit on the rise), and every
/// follower then takes its owner step in one substep.
enum class LayerSteps : std::uint8_t { Fixed, Variable, VariableCommon };

/// What a fine side does with its ghosts J and what it sends (docs/multirate.md "lts"):
///   Layer: J moves linearly in time between the owner's u_J(T) and u_J(T + H); g_A(T) is the
///     layer's force on J at the owner instant T.
///   Lts: leapfrog local time stepping (Diaz & Grote 2009, SIAM J. Sci. Comput. 31, 3.2-3.3), in
///     its physical-state form (coupling-study/lts/lts_physical_form.py): the fine side runs
///     ordinary central differences at h = H / p; over [T, T + H] J moves on the reflected path
///     U(T + q h) = 2 u_J(T) - U(T - q h), q = 1..p-1 (frozen at u_J(0) over the first owner
///     step), and lands on the owner's u_J(T + H); the force sent for T is the hat average of the
///     layer's force on J over (T - H, T + H), Fbar(T) = sum_q (1/p)(1 - |t_q - T|/H) g(t_q) over
///     the fine instants t_q (one-sided, weights doubled, over the first and the last owner
///     step), sent once its last instant T + (p-1) h is done. The coarse side is the same for both.
///     Rotations (shell J) alike, as small rotations: J's angular velocity over substep q is the
///     mirror substep's of the owner step before, and over the last one what lands on the owner's
///     rotation at T + H; the moments hat-averaged as the forces.
///     Conserves LtsEnergy's E in the linear case with fixed steps. The
///     elements on J compute no bulk viscosity (the path's velocity is no physical one:
///     Solver::set_ghost_bulk_viscosity).
///     Variable steps (LayerSteps::Variable; layer_stepper_lts_variable.cpp): the fine side runs
///     most of an owner step before the owner's u_J at its end exists, so every owner step is
///     announced one ahead: the first is the plan's, each later one rides on the u_J of the
///     instant it starts at (LayerMessage::next_step). The path reflects the owner step before
///     in time (interpolated where the steps differ), and Fbar(T) weighs the two one-sided hat
///     averages by the owner steps on either side of T. No E: it needs one coarse step.
enum class LayerForm : std::uint8_t { Layer, Lts };

/// A vector sent to a partner. Displacement: owner -> ghost holder, u_J(time) [m] and
/// omega_J(time - H/2) [rad/s] (`second`, empty when no J node rotates). Force: ghost holder ->
/// owner, g_A(time) [N] and the moment [N m] (`second`, empty when no J node rotates). Every
/// vector is [3 n_J], xyz interleaved, J in Interface::j_nodes_global order.
struct LayerMessage {
  enum class Kind : std::uint8_t { Displacement, Force };
  Kind kind = Kind::Displacement;
  std::uint32_t interface_index = 0;
  Tick time = 0;
  std::vector<double> first;
  std::vector<double> second;
  /// Force, variable steps: the sender's step proposal at `time` [ticks] (0: no limit, a domain
  /// of rigid bodies only). 0 and unused with fixed steps.
  Tick proposal = 0;
  /// Displacement, variable steps: the owner's run ends at `time` (its holder ends there too).
  bool last = false;
  /// Displacement, variable steps: the owner pauses at `time` (advance()'s `until`: a checkpoint),
  /// and its holder pauses there with it.
  bool pause = false;
  /// Displacement, lts with variable steps: the owner's step after `time` [ticks], the owner step
  /// [time, time + next_step] that the holder substeps next (its fine side runs most of it before
  /// the owner's u_J at its end exists); 0 when the owner ends at `time`.
  Tick next_step = 0;
};

/// History rows of one fine-side interface (coupling/layer_work.h), for the coordinator.
struct LayerRows {
  std::uint32_t interface_index = 0;
  std::vector<coupling::LayerSample> rows;
};

/// Cycle t -> t + h of this domain (h = step()):
///   begin_cycle()                                        (state at t sampled: on_sample)
///   fine ports: need u_J(T') for the owner instant T' >= t + h      -> Wait::Displacement
///   set_ghost_displacement / set_ghost_angular_velocity, end_cycle_positions()
///   coarse ports: send u_J(t + h), omega_J(t + h/2), unless sent ahead -> on_outbox
///     (see below; sent ahead: checked against the passes instead)
///   end_cycle_compute()                                  (overlaps the partners' work)
///   fine ports at an owner instant (t + h = k H): send g_A(t + h)    -> on_outbox
///   coarse ports: need g_A(t + h)                                   -> Wait::Force
///   add_coupling_force/moment
///   coarse ports: send u_J(t + 2h), omega_J(t + 3h/2) predicted now  -> on_outbox
///   end_cycle_accelerations(), impose_step(h)
/// The prediction (Solver::predict_next_positions) is the arithmetic the next cycle's nodal passes
/// will do on J: it takes the owner's whole tail (accelerations, velocities and positions of every
/// node) off the round trip the fine side waits on. The next cycle checks that the passes gave the
/// same bits and sends nothing more (a std::logic_error, naming the node otherwise: a bug,
/// exit 4). Ports whose J nodes move otherwise (rigid, prescribed) send after the passes, as does
/// the first cycle after initialize() or restore_state().
/// The run ends after the cycle whose begin_cycle() finds t >= end_time (Solver::finished()).
class LayerStepper {
 public:
  enum class Wait : std::uint8_t {
    None,          ///< can advance
    Displacement,  ///< a fine port needs the owner's next u_J
    Force,         ///< a coarse port needs the holder's g_A at the current instant
    Finished,      ///< end time reached
  };

  /// `solver` (ghosts, mass and inertia overrides set, not initialised) must outlive the stepper.
  /// Fixed steps: `step` is this domain's step in ticks; every fine port's partner_step must be a
  /// whole multiple of it (ModelError otherwise, with both values). Variable steps: `step` is
  /// ignored; ModelError when the fine ports name more than one partner.
  LayerStepper(integration::Solver& solver, std::vector<LayerPort> ports, Tick step,
               std::int64_t ticks_per_second, LayerSteps steps = LayerSteps::Fixed);

  /// After Solver::initialize() (the caller's: a daemon registers the initial stable step first):
  /// imposes the step, queues g_A(0) of every fine port (t = 0: a coarse port needs it to complete
  /// a^0, exchange_initial_forces' rule). Throws ModelError when the step exceeds the solver's
  /// stable step (Solver::impose_step).
  void initialize();

  /// Delivers a partner's message (any order across interfaces; in time order per interface).
  /// Throws ProtocolError-like ModelError for an unknown interface, a wrong kind for the port's
  /// side, a wrong length, or a time that is not the next one expected.
  void deliver(LayerMessage m);

  /// Runs cycles until it must wait, the run is finished, or it pauses at the start of a cycle
  /// (returns Wait::None, nothing begun: call again to go on); calls on_sample after every
  /// begin_cycle() (the state at time() complete). Returns why it stopped. A domain finishes at its
  /// first instant >= the end time that is also an instant of every owner it holds ghosts of.
  /// Pauses: fixed steps and variable leaders at their first instant >= until; a variable follower
  /// where its owner pauses (the instants it lands on are its owner's, not the multiples of
  /// `until`), which the owner's u_J says (LayerMessage::pause), as long as `until` <= that
  /// instant. So a whole tree of domains pauses at its leader's first instant >= until, to the
  /// tick, as a checkpoint needs, and stays there until called with a later `until`. The leader
  /// marks the u_J it sends from the `until` of the call that sends it (nothing is sent ahead
  /// across a pause): call every domain with the same `until` until all have paused. Lts with
  /// variable steps: a follower pauses at the start of the owner step that begins where its owner
  /// pauses, and its owner reaches that instant only with the Fbar this side sends p - 1
  /// substeps later, so the tree pauses only if each domain goes on after its pause (the daemons
  /// write and go on; LayerNetwork::run refuses such a pause).
  Wait advance(const std::function<void()>& on_sample = {},
               Tick until = std::numeric_limits<Tick>::max());

  /// Messages produced so far, to be sent in order; take_outbox() empties the queue.
  std::deque<LayerMessage> take_outbox();
  /// Called by advance() as soon as it has queued a message it will not wait on before its next
  /// computation: u_J(t + h) as soon as g_A(t) is applied (predicted; or right after the positions
  /// at t + h, see the class comment), before this domain's nodal passes and forces, and
  /// g_A(t + h) right after those forces. A daemon takes the outbox there and sends it, so that
  /// the partner computes while this domain computes its forces instead of taking turns
  /// (docs/design.md §2.6 "Overlap"). Unset (LayerNetwork), the messages wait in the outbox until
  /// advance() returns. Only when messages leave changes: the messages and the numbers do not.
  void set_on_outbox(std::function<void()> on_outbox) { on_outbox_ = std::move(on_outbox); }
  bool has_outbox() const { return !outbox_.empty(); }

  /// Interface histories: with recording on (a daemon; off by default, LayerNetwork keeps none),
  /// each fine port adds a row at every owner instant T from the g_A(T) it sends and the u_J(T)
  /// it received (coupling::LayerWorkMeter); take_history() returns the rows since the last
  /// call, fine ports without new rows left out.
  void set_record_history(bool on) { record_history_ = on; }
  std::vector<LayerRows> take_history();
  const std::deque<LayerMessage>& outbox() const { return outbox_; }  ///< not taken yet

  /// Checkpoints (layer_stepper_state.cpp, docs/design.md §2.6 "Checkpoints"). At a cycle boundary
  /// (advance() returned Wait::None: it paused, outbox empty): the phase, the time and every
  /// port's owner step in use, with the ghost targets; variable steps: the step chosen (leader) or
  /// the owner step just ended and the proposal sent with g_A(t) (follower, which pauses only at
  /// the end of an owner step). Messages already received for
  /// later instants are left out (their senders send them again after a restart: a faster partner
  /// computes them again; a coarse side that sent u_J(t + h) ahead before stopping at t sends it
  /// after its positions, since a restored stepper has sent nothing ahead), and the port's next
  /// expected time is that of the first of them. Throws ModelError when not at a cycle boundary,
  /// with messages queued to send, or holding a received message for an instant <= time()
  /// (unconsumed).
  void save_state(core::StateWriter& w) const;
  /// Instead of initialize(), after the solver's own restore_state(), and after
  /// set_proposal_limits(): resumes at the saved instant. Throws CheckpointError if the saved
  /// steps (fixed: the step; variable: the step safety and cap), tick or ports differ from this
  /// stepper's.
  void restore_state(const core::StateReader& r);
  /// advance() stopped between two cycles (at `until`) or has not started.
  bool at_cycle_boundary() const { return phase_ == Phase::Begin; }

  /// u_J messages of the coarse ports so far, and how many of them left ahead of the nodal passes
  /// (Solver::predict_next_positions): all but each port's first since initialize() or
  /// restore_state(), unless one of its J nodes is rigid or prescribed.
  std::int64_t displacements_sent() const { return displacements_sent_; }
  std::int64_t displacements_sent_ahead() const { return displacements_ahead_; }

  /// Fixed steps: the run's end instant in ticks instead of controls.end_time, before advance():
  /// the end rounded up to the plan's base period (coupling::aligned_end), so that every
  /// domain of a chain ends at the same instant (a fine domain would otherwise end at its owner's
  /// first instant after the end time while that owner goes on to its own owner's). ModelError
  /// for a negative value or with variable steps (their `last` flag does it).
  void set_end_time(Tick end);
  /// Before initialize(): the form (LayerForm). Lts: `energy_period` is the coarse step of the
  /// conserved energy's instants (every domain's: the plan's base), at whose multiples the stepper
  /// samples its share (lts_energy_J; fixed steps only: variable steps have no E). ModelError for
  /// a period that is not a multiple of this domain's step and of every owner's (fixed steps), a
  /// first owner step that is not a multiple of this domain's planned step, or `split` (variable).
  void set_form(LayerForm form, Tick energy_period = 0);
  LayerForm form() const { return form_; }
  /// Lts: this domain's share of E^{k-1/2} (LtsEnergy) at the last coarse instant (a multiple of
  /// the energy period) it evaluated; ready once that instant and the two before it were sampled
  /// and the last sample was evaluated (every instant, unless set_lts_energy_wanted filters).
  bool lts_energy_ready() const { return form_ == LayerForm::Lts && lts_energy_.ready(); }
  double lts_energy_J() const { return lts_energy_.value_J(); }
  /// Lts: this domain's share at `instant` [ticks] if it is one of the last two it evaluated (the
  /// result file's rows of a history instant take the share of the last coarse instant before it,
  /// which every domain holds: io::GlstatSample::scheme_energy_J); NaN otherwise or before it is
  /// ready.
  double lts_energy_at_J(Tick instant) const {
    for (int k = 0; k < 2; ++k)
      if (lts_sampled_at_[k] == instant) return lts_sampled_J_[k];
    return std::numeric_limits<double>::quiet_NaN();
  }
  Tick lts_energy_period() const { return energy_period_; }
  /// Lts: the rim elements' plastic state is settled at time() (an owner instant of every fine
  /// port, where the deferred J2 returns are taken: Solver::set_rim_returns); between owner
  /// instants the rim holds its elastic trial, which a field state should not show. Always true
  /// for `layer` and for a domain that holds no ghosts.
  bool rim_settled() const { return form_ != LayerForm::Lts || lts_owner_instant(t_); }
  /// Messages dropped as a partner's repeats after a restore (deliver; docs/checkpoints.md).
  std::int64_t repeats_dropped() const { return repeats_dropped_; }
  /// Lts: the coarse instants [ticks] whose share someone reads (a daemon: its history rows').
  /// The stepper then samples only those and the two before each, not every coarse instant
  /// (unset: every one). The shares read are the same bits either way.
  void set_lts_energy_wanted(std::function<bool(Tick)> wanted) {
    lts_energy_wanted_ = std::move(wanted);
  }
  /// Variable steps, before initialize(): proposals are min(the solver's, max_step_s) (if > 0),
  /// and a leader takes `leader_safety` (0, 1] of its own (the margin fixed steps keep on the
  /// coarse side: the layer coupling's error grows with the coarse Courant number). ModelError
  /// for values out of range.
  void set_proposal_limits(double leader_safety, double max_step_s);
  Tick time() const { return t_; }  ///< this domain's current instant
  /// controls.end_time_s in ticks (nearest), or set_end_time's
  Tick end_time() const { return end_; }
  Tick step() const { return h_; }  ///< the step of the cycle about to begin (0: not known yet)
  std::int64_t ticks_per_second() const { return ticks_per_second_; }
  double seconds(Tick n) const;
  Wait waiting() const { return wait_; }
  /// The interface index this stepper waits on (valid when waiting() is Displacement or Force).
  std::uint32_t waiting_interface() const { return wait_iface_; }
  const integration::Solver& solver() const { return solver_; }
  const std::vector<LayerPort>& ports() const { return ports_; }

 private:
  /// Positions: u(t + h) and the interior elements' forces, which need no partner; Rim: the
  /// ghosts' motion u_J(t + h) (waits for it), the other forces, g_A(t + h) sent.
  enum class Phase : std::uint8_t { Initial, Begin, Positions, Rim, Accelerations, Done };
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct PortState {
    std::deque<LayerMessage> inbox;  ///< received, not consumed yet
    Tick next_expected = 0;          ///< time of the next message from the partner
    Tick drop_before = -1;      ///< restored: the partner's messages before this instant are resent
    std::vector<double> u_T;    ///< fine side: u_J(T) of the current owner step
    std::vector<double> u_1;    ///< fine side: u_J(T + H)
    std::vector<double> omega;  ///< fine side: omega_J(T + H/2)
    Tick T = 0;                 ///< fine side: the owner step [T, T + H] in use
    Tick T1 = 0;                ///< fine side: T + H, once u_1 is in
    bool have_u1 = false;       ///< fine side: u_1 received for this owner step
    bool rotates = false;       ///< J has rotational dofs (shell nodes)
    Tick sent_ahead = -1;       ///< coarse side: u_J of this instant sent early
    std::vector<double> ahead_u, ahead_omega;  ///< coarse side: what was sent early
    coupling::LayerWorkMeter meter;            ///< fine side: the interface history
    std::vector<coupling::LayerSample> rows;   ///< fine side: rows not taken yet
    // Lts, fine side (LayerForm):
    std::int64_t substeps = 1;       ///< p = H / h
    std::vector<double> path_prev;   ///< [(p + 1) 3 n_J] J at T - H + q h, q = 0..p
    std::vector<double> path_cur;    ///< [(p + 1) 3 n_J] J at T + q h, as far as applied
    std::vector<double> fbar_T;      ///< [3 n_J] Fbar(acc_T) so far [N]
    std::vector<double> fbar_T1;     ///< [3 n_J] Fbar(acc_T + H) so far [N]
    std::vector<double> omega_prev;  ///< rotates: [p 3 n_J] J's omega over T - H + [q h, (q+1) h]
    std::vector<double> omega_cur;   ///< rotates: [p 3 n_J] over T + [q h, (q+1) h], as applied
    std::vector<double> mbar_T, mbar_T1;  ///< rotates: [3 n_J] the moments' Fbar alike [N m]
    Tick acc_T = 0;                       ///< the owner instant fbar_T is for
    /// Restored at an owner instant T > 0 with p > 1: the owner used Fbar(T) before its
    /// checkpoint, so it is not sent again (-1: none).
    Tick consumed = -1;
    // Lts with variable steps (layer_stepper_lts_variable.cpp):
    std::vector<Tick> path_prev_t, path_cur_t;  ///< the instants of path_prev's / path_cur's rows
    std::vector<double> fbar_left;       ///< [3 n_J] the left half of Fbar(acc_T), complete [N]
    std::vector<double> g_T;             ///< [3 n_J] g(acc_T) [N]
    std::vector<double> mbar_left, m_T;  ///< rotates: the moments' alike [N m]
    Tick H_prev = 0;                     ///< the owner step that ended at acc_T (0: t = 0)
    Tick next_step_1 = 0;  ///< LayerMessage::next_step of the u_J(T1) consumed (have_u1)
    bool last_1 = false;   ///< LayerMessage::last of the u_J(T1) consumed
    bool pause_1 = false;  ///< LayerMessage::pause of the u_J(T1) consumed
  };

  Tick to_ticks_end(double t_s) const;
  bool at_owner_instant(const LayerPort& port) const;
  bool finished_here() const;
  void apply_initial_forces();
  bool ghost_targets_ready();
  void send_displacements();
  void send_displacements_ahead();
  LayerMessage displacement_message(const LayerPort& port) const;
  void send_forces();
  // Lts (layer_stepper_lts.cpp).
  void lts_start_port(const LayerPort& port, PortState& ps) const;
  void lts_next_owner_step(PortState& ps) const;
  void lts_ghost_targets(const LayerPort& port, PortState& ps, Tick t1);
  void lts_send_forces();
  /// Whether t is an owner instant of every fine-side port: where the rim's deferred J2 returns
  /// are taken (Solver::set_rim_returns; every instant without a fine-side port or at p = 1).
  bool lts_owner_instant(Tick t) const;
  void lts_start_energy();
  // Lts with variable steps (layer_stepper_lts_variable.cpp; docs/multirate.md "Variable steps
  // under lts").
  void lts_ghost_targets_variable(const LayerPort& port, PortState& ps, Tick t1);
  void lts_send_forces_variable();
  void lts_next_owner_step_variable(PortState& ps) const;
  /// The row of Fbar(m.time); `keep` false: only the meter moves on (restored past it).
  void lts_record_row(PortState& ps, const LayerMessage& m, Tick H_before, bool keep = true);
  /// Sends Fbar (m) unless the owner used it before the checkpoint this side restored from.
  void lts_send_fbar(PortState& ps, LayerMessage m, Tick H_before);
  /// At the instant t_, its forces in: the step to take next and, with holders, announced_ (the
  /// one after). false: waits for the owner's u_J (the next owner step may have been taken up;
  /// the call after the wait finds it taken and goes on from there).
  bool lts_plan_next(Tick& next);
  bool lts_variable() const { return variable_ && form_ == LayerForm::Lts; }
  /// A follower: the owner step after the current one, from the owner's u_J at the current one's
  /// end (consumed, or at the inbox front): owner_last_, owner_pause_, next_owner_H_ and
  /// next_substeps_ (ceil(H / the proposal sent with the last Fbar)). false: that u_J is not in
  /// yet.
  bool lts_decide_next_owner_step();
  /// The step after the one of `index` (0-based) in the current owner step, or the first of the
  /// next owner step (waits for it: false), which a domain with holders announces with its u_J
  /// (LayerMessage::next_step). A leader: its choice (choose_step) after `next`.
  bool lts_step_after(std::int64_t index, Tick next, Tick& after);
  /// Substep j of n of an owner step of H ticks: H / n whole ticks, the last H mod n of them a
  /// tick longer (no substep shorter than the others by more than a tick: docs/design.md §2.7).
  static Tick substep_length(Tick H, std::int64_t n, std::int64_t j) {
    return H / n + (j >= n - H % n ? 1 : 0);
  }
  /// At a coarse instant t_ (a multiple of energy_period_): LtsEnergy::sample if wanted.
  void lts_sample_energy();
  bool forces_ready();
  void apply_forces();
  void flush_outbox();
  /// Fixed steps: Solver::impose_step(h_), its NumericalError completed with the fix.
  void impose_fixed_step();
  // Variable steps.
  Tick proposal_ticks() const;
  Tick subtree_proposal() const;         ///< variable common: the least of own and holders' g_A(t_)
  bool forces_wait_for_holders() const;  ///< variable common: g_A(t) after the holders' g_A(t)
  /// A leader's next step, from the holders' g_A (inbox fronts). Of H = p_own and H = m p_k
  /// (m = floor(p_own / p_k) >= 1, for each holder k) it takes the one with the least cost per
  /// unit time (w_own + sum_k w_k ceil(H / p_k)) / H, w = element counts (the ratio just above a
  /// whole number costs one substep more, or a shorter coarse step). Variable common: the least
  /// proposal of all (subtree_proposal()).
  Tick choose_step() const;
  bool at_owner_end() const;       ///< a follower at the end T + H of its owner step
  bool finishes_at(Tick t) const;  ///< variable: this domain's run ends at instant t
  bool pauses_at(Tick t) const;    ///< variable: this domain pauses at instant t (u_J's flag)
  bool pause_here() const;         ///< advance() pauses at t_
  /// A variable leader about to pause at t_: it sends nothing ahead, so that the u_J(t_ + h) it
  /// sends after the pause is marked against the `until` of the call that sends it.
  bool pausing_now() const;
  bool start_owner_step();  ///< false: waits for the owner's next u_J
  /// A follower's next step inside the owner step H: H / n whole ticks, n = ceil(H / p)
  /// (LayerSteps), the last ones a tick longer when n does not divide H.
  Tick next_substep() const { return substep_length(owner_H_, substeps_, substep_); }

  integration::Solver& solver_;
  std::vector<LayerPort> ports_;
  std::vector<PortState> state_;
  Tick h_ = 0, t_ = 0, end_ = 0;
  bool initialized_ = false;
  bool record_history_ = false;
  bool variable_ = false;           ///< LayerSteps::Variable or VariableCommon
  bool common_ = false;             ///< LayerSteps::VariableCommon
  bool follower_ = false;           ///< variable: has fine ports (its owner sets its owner steps)
  bool step_pending_ = false;       ///< variable follower: the next step awaits the owner's u_J
  Tick proposal_sent_ = 0;          ///< variable follower: the proposal sent with g_A(T)
  double leader_safety_ = 1.0;      ///< variable leader: factor on its own proposal
  double max_step_s_ = 0.0;         ///< variable: > 0 caps every proposal
  std::int64_t substeps_ = 1;       ///< variable follower: n of the owner step in use
  std::int64_t substep_ = 0;        ///< variable follower: index of the step about to be taken
  Tick owner_T_ = 0, owner_H_ = 0;  ///< variable follower: the owner step [T, T + H] in use
  bool owner_last_ = false;         ///< variable follower: the owner ends at T + H
  bool owner_pause_ = false;        ///< variable follower: the owner pauses at T + H
  // Lts with variable steps: the first owner step is the plan's, every later one announced
  // (LayerMessage::next_step).
  Tick planned_h_ = 0;              ///< the step the plan gave (the first cycle's)
  Tick announced_ = 0;              ///< the step after the next instant, sent with u_J
  bool next_owner_known_ = false;   ///< follower: next_owner_H_ / next_substeps_ decided
  Tick lts_pause_at_ = -1;          ///< follower: pauses there (the owner step taken up there)
  Tick next_owner_H_ = 0;           ///< follower: the owner step after the current one
  std::int64_t next_substeps_ = 1;  ///< follower: its substeps
  std::vector<std::pair<std::size_t, double>> lts_overlap_;  ///< scratch: omega_prev's weights
  Tick until_ = std::numeric_limits<Tick>::max();  ///< advance()'s `until` (a leader's pause)
  std::int64_t ticks_per_second_ = 0;
  Phase phase_ = Phase::Initial;
  Wait wait_ = Wait::None;
  std::uint32_t wait_iface_ = 0;
  std::deque<LayerMessage> outbox_;
  std::function<void()> on_outbox_;
  std::int64_t displacements_sent_ = 0, displacements_ahead_ = 0;
  std::vector<double> ghost_u_, ghost_omega_;  ///< [3 n_ghost] Solver::ghost_nodes() order
  std::vector<std::size_t> ghost_slot_;        ///< [n_local] position in the ghost list
  LayerForm form_ = LayerForm::Layer;
  Tick energy_period_ = 0;  ///< Lts: the conserved energy's coarse step [ticks]
  LtsEnergy lts_energy_;
  std::int64_t repeats_dropped_ = 0;             ///< repeats_dropped()
  std::function<bool(Tick)> lts_energy_wanted_;  ///< set_lts_energy_wanted's (empty: all)
  Tick lts_sampled_at_[2] = {-1, -1};            ///< the last two evaluated instants, newest first
  double lts_sampled_J_[2] = {std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN()};
};

}  // namespace crashlink::cosim
