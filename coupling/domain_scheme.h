#pragma once
// A coupling scheme as one domain's daemon sees it (docs/design.md §2.6, §2.7): the domain's
// solver and the scheme's state machine, with no IO. The daemon (daemon.cpp) is a message pump
// between its transport and this object: it sends what take_outbox() gives, delivers what comes,
// calls advance() until the end, saves and restores the state at checkpoints. Implemented by
// `layer` (solver/daemon/layer_domain_scheme.h: cosim::LayerStepper) and `paper`
// (solver/daemon/paper_domain_scheme.h: the free state / correction cycle of [8]-[11]); the
// schemes are listed in apps/schemes.h.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/state_archive.h"
#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"
#include "solver/integration/solver.h"

namespace crashlink::coupling {

/// Why advance() returned.
enum class Pace : std::uint8_t {
  Paused,    ///< between two cycles (at `until`, or to let the daemon serve): call again
  Waiting,   ///< needs a message from a partner or the coordinator: deliver() it, then advance()
  Finished,  ///< the end instant is reached and sampled
};

/// A message the scheme wants sent. interface_index >= 0: a vector for the partner on that
/// interface, which may go on the partner's lane (docs/processes.md "Lanes"); -1: to the
/// coordinator.
struct Outgoing {
  wire::Envelope envelope;
  std::int64_t interface_index = -1;
};

/// A partner this domain exchanges vectors with on one interface (for its lane).
struct LanePartner {
  std::uint32_t interface_index = 0;
  std::string partner;      ///< the partner domain's name
  std::size_t j_nodes = 0;  ///< the vectors' length in nodes (sizes a shared-memory ring)
};

/// What a scheme is given when it is built, beside the scenario's cut.
struct DomainSchemeOptions {
  std::string domain;        ///< the domain's name (messages)
  double step_safety = 1.0;  ///< factor on the solver's stable step in proposals
  double max_step_s = 0.0;   ///< > 0: caps the proposals
  int threads = 1;           ///< the solver's (integration::Solver::set_threads)
};

class DomainScheme {
 public:
  virtual ~DomainScheme() = default;

  /// The coordinator's tick (its Hello), before fill_register().
  virtual void set_ticks_per_second(std::int64_t tps) = 0;

  virtual integration::Solver& solver() = 0;
  virtual const integration::Solver& solver() const = 0;
  /// The instant reached, ticks.
  virtual Tick time() const = 0;

  /// The scheme's vectors may travel daemon to daemon (docs/processes.md "Lanes"): the daemon then
  /// offers a lane (false: everything goes through the coordinator).
  virtual bool uses_lanes() const = 0;
  /// The interfaces whose vectors travel on the partners' lanes, when there are lanes.
  virtual std::vector<LanePartner> lane_partners() const = 0;
  /// A message that may come on a lane (a partner's vector); anything else there is a protocol
  /// error of the lane.
  virtual bool lane_message(const wire::Envelope& e) const = 0;

  /// This scheme's part of the Register (the interface nodes, their masses and positions).
  virtual void fill_register(wire::Register& r) const = 0;

  /// The coordinator's Setup, checked against this domain's cut (ProtocolError naming the values
  /// otherwise). Returns true when the solver was replaced by another (the daemon then moves what
  /// refers to it; the old one lives until initialize()). Fresh start or restart follows:
  /// initialize() or restore_state().
  virtual bool start(const wire::Setup& setup) = 0;
  /// A fresh start, after start().
  virtual void initialize() = 0;

  /// Runs cycles until it pauses (at the first instant >= until), waits for a message or
  /// finishes; calls on_sample after every Solver::begin_cycle() (the state at time() complete).
  virtual Pace advance(const std::function<void()>& on_sample, Tick until) = 0;
  /// Hands every message produced so far to `send`, in the order they must leave, and forgets
  /// them.
  virtual void drain_outbox(const std::function<void(const Outgoing&)>& send) = 0;
  /// Called as soon as a message is queued that the domain will not wait on before its next
  /// computation (so partners compute at the same time: docs/design.md §2.6 "Overlap").
  virtual void set_on_outbox(std::function<void()> on_outbox) = 0;
  /// A message from a partner or the coordinator. Throws ProtocolError for one the scheme does not
  /// expect (naming it and the domain).
  virtual void deliver(wire::Envelope&& e) = 0;

  /// Progress for the coordinator (checkpoint: written right before a checkpoint); nullopt when
  /// the scheme sends none.
  virtual std::optional<wire::Envelope> report(bool checkpoint) = 0;
  /// This scheme's part of the Bye's report.
  virtual void fill_bye(wire::DomainReport& r) const = 0;

  /// The scheme's conserved discrete energy: this domain's share [J] at the last coarse instant
  /// at or before `instant_s`, and that instant [s] (io::GlstatSample::scheme_energy_J and
  /// scheme_energy_time_s of the row of that history instant; `lts`: cosim::LtsEnergy); NaN for
  /// a scheme without one.
  virtual std::pair<double, double> scheme_energy(double /*instant_s*/) const {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }

  /// Whether the state at this instant is one a field state may show: `lts`'s fine side holds its
  /// rim elements' elastic trial between owner instants (docs/multirate.md "Plasticity on the
  /// rim"), so its field states wait for the next owner instant.
  virtual bool fields_settled() const { return true; }

  /// Checkpoints (docs/design.md §2.6 "Checkpoints"), at a cycle boundary after Pace::Paused.
  virtual bool at_cycle_boundary() const = 0;
  virtual Tick end_time() const = 0;
  virtual void save_state(core::StateWriter& w) const = 0;
  virtual void restore_state(const core::StateReader& r) = 0;
};

/// This domain's step proposal in whole ticks, floor(step_safety * min(dt, max_step_s) * tps), dt
/// the solver's stable step (cosim::LayerNetworkOptions' rule, so that both plan the same steps);
/// 0: no limit (no deformable element). Throws ModelError below one tick.
std::int64_t proposal_ticks(const integration::Solver& s, const DomainSchemeOptions& o,
                            std::int64_t ticks_per_second);

/// The step a domain proposes under variable steps, without the step safety [s]: the solver's
/// step_proposal() capped by max_step_s (> 0). What cosim::LayerStepper::proposal_ticks sends, the
/// Register's own_step_ticks and LayerNetwork's plan of lts's first owner step read.
double own_step_s(const integration::Solver& s, double max_step_s);
/// own_step_s in whole ticks (TickClock::step_to_ticks); 0 when there is no limit (no deformable
/// element: infinite, or >= 1e3 s) or it is below one tick (the stepper says why).
std::int64_t own_step_ticks(const integration::Solver& s, double max_step_s,
                            std::int64_t ticks_per_second);

}  // namespace crashlink::coupling
