#include "solver/daemon/paper_domain_scheme.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"
#include "proto/envelope_name.h"
#include "solver/daemon/paper_port.h"

namespace crashlink::daemon {

namespace {

class PaperDomainScheme final : public coupling::DomainScheme {
 public:
  PaperDomainScheme(const partition::Decomposition& dec, coupling::DomainSchemeOptions o)
      : o_(std::move(o)), port_(build_paper_port(dec, o_.domain)) {
    port_.solver->set_threads(o_.threads);
  }

  integration::Solver& solver() override { return *port_.solver; }
  const integration::Solver& solver() const override { return *port_.solver; }
  coupling::Tick time() const override { return time_; }
  void set_ticks_per_second(std::int64_t tps) override { tps_ = tps; }
  bool uses_lanes() const override { return false; }
  std::vector<coupling::LanePartner> lane_partners() const override { return {}; }
  bool lane_message(const wire::Envelope& /*e*/) const override { return false; }

  void fill_register(wire::Register& r) const override {
    const auto& sub = port_.solver->model();
    for (std::size_t j = 0; j < port_.nodes.size(); ++j) {
      const auto l = port_.nodes[j].local;
      r.add_node_ids(sub.nodes.id[l]);
      r.add_masses_kg(port_.own_mass_kg[j]);
      for (std::size_t d = 0; d < 3; ++d) r.add_positions_m(sub.nodes.x0[3 * l + d]);
    }
  }

  /// The Setup's summed masses ([5]; the solver is rebuilt if they differ in any bit from the
  /// cut's); `paper` has no checkpoints and no restart.
  bool start(const wire::Setup& setup) override {
    if (setup.ticks_per_second() != tps_ || setup.step_ticks() < 1)
      throw ProtocolError(
          "coordinator",
          fmt::format("`paper` Setup for domain '{}' with step {} ticks at {} ticks "
                      "per second (Hello: {})",
                      o_.domain, setup.step_ticks(), setup.ticks_per_second(), tps_));
    if (setup.restart() || setup.options().checkpoint_interval_ticks() > 0)
      throw ProtocolError("coordinator",
                          fmt::format("the `paper` Setup of domain '{}' asks for checkpoints or a "
                                      "restart; `paper` runs have neither (use `layer`)",
                                      o_.domain));
    step_ = setup.step_ticks();
    if (auto fresh = use_summed_masses(port_, setup, o_.domain)) {
      fresh->set_threads(o_.threads);
      fresh->initialize();
      retired_ = std::move(port_.solver);  // what refers to it moves first (the recorder)
      port_.solver = std::move(fresh);
      return true;
    }
    return false;
  }

  void initialize() override { retired_.reset(); }

  /// docs/design.md §2.6: the free state at t leaves, its Correction comes (deliver), is applied,
  /// the cycle begins (energies at t, guard, output), the imposed step is taken; the next free
  /// state carries the energies at t.
  coupling::Pace advance(const std::function<void()>& on_sample,
                         coupling::Tick /*until*/) override {
    if (!correction_) {
      if (!sent_) queue_free_state();
      return coupling::Pace::Waiting;
    }
    auto& s = *port_.solver;
    const wire::Correction& c = *correction_;
    apply_correction(port_, c, o_.domain);
    // At the end no step follows; the last one (or the stable step, if it shrank below it)
    // keeps the last kinetic energy (product form, v^{n+1/2} over dt^{n+1/2}) on the steps the
    // run took, as in every cycle before.
    if (!c.stop()) step_ = c.imposed_step_ticks();
    const double step_s = static_cast<double>(step_) / static_cast<double>(tps_);
    s.impose_step(c.stop() ? std::min(step_s, s.dt_s()) : step_s);
    s.begin_cycle();
    if (on_sample) on_sample();
    energy_ = energy_terms(port_);
    energy_time_ = time_;
    if (c.stop()) return coupling::Pace::Finished;
    s.end_cycle_forces();
    s.end_cycle_accelerations();
    time_ += c.imposed_step_ticks();
    correction_.reset();
    queue_free_state();
    return coupling::Pace::Waiting;
  }

  void drain_outbox(const std::function<void(const coupling::Outgoing&)>& send) override {
    if (!queued_) return;
    queued_ = false;
    send(out_);
  }

  void set_on_outbox(std::function<void()> /*on_outbox*/) override {}

  /// The Correction of the free state at time_.
  void deliver(wire::Envelope&& e) override {
    if (!e.has_correction())
      throw ProtocolError("coordinator",
                          fmt::format("domain '{}' expected the Correction of its free state at "
                                      "tick {}, got a {}",
                                      o_.domain, time_, wire::body_name(e)));
    if (correction_ || !sent_ || e.correction().time_ticks() != time_)
      throw ProtocolError("coordinator",
                          fmt::format("domain '{}' got a Correction for tick {}; its free state "
                                      "is at tick {}",
                                      o_.domain, e.correction().time_ticks(), time_));
    correction_ = std::move(*e.mutable_correction());
    sent_ = false;
  }

  std::optional<wire::Envelope> report(bool /*checkpoint*/) override { return std::nullopt; }
  void fill_bye(wire::DomainReport& r) const override {
    *r.mutable_energy() = energy_;  // the guard's last sample
  }

  bool at_cycle_boundary() const override { return false; }
  coupling::Tick end_time() const override { return std::numeric_limits<coupling::Tick>::max(); }
  void save_state(core::StateWriter& /*w*/) const override {
    throw ModelError("`paper` keeps no checkpoints (use `layer`)");
  }
  void restore_state(const core::StateReader& /*r*/) override {
    throw ModelError("`paper` keeps no checkpoints (use `layer`)");
  }

 private:
  /// The free state at time_ with this domain's own proposal (the coordinator imposes it with
  /// variable steps, its plan with fixed ones).
  void queue_free_state() {
    fill_free_state(port_, time_, proposal(), energy_, energy_time_, out_.envelope);
    queued_ = true;
    sent_ = true;
  }

  /// coupling::proposal_ticks, with a stable step that collapsed (NaN, or below one tick) ending
  /// the run as the numerical failure it is.
  std::int64_t proposal() const {
    const auto& s = *port_.solver;
    const double dt = s.dt_s();
    if (std::isnan(dt) ||
        (std::isfinite(dt) && !(o_.step_safety * dt * static_cast<double>(tps_) >= 1.0)))
      throw NumericalError(fmt::format(
          "the stable step is {:.6e} s (set by {}), below one tick of 1/{} s: the mesh has "
          "collapsed there; fix: check that element's material, contact and loading",
          dt, s.critical_element(), tps_));
    return coupling::proposal_ticks(s, o_, tps_);
  }

  coupling::DomainSchemeOptions o_;
  PaperPort port_;
  std::unique_ptr<integration::Solver>
      retired_;  ///< the solver start() replaced, until initialize()
  std::int64_t tps_ = 0;
  coupling::Tick time_ = 0;          ///< the instant of the next free state
  coupling::Tick step_ = 0;          ///< the last imposed step (first: the Setup's)
  wire::EnergyTerms energy_;         ///< the energies at the last begun instant
  coupling::Tick energy_time_ = -1;  ///< their instant (-1: none yet)
  coupling::Outgoing out_;           ///< the free state (reused: its arrays keep their capacity)
  bool queued_ = false;              ///< out_ waits to leave
  bool sent_ = false;                ///< the free state at time_ is out, its Correction not in
  std::optional<wire::Correction> correction_;
};

}  // namespace

std::unique_ptr<coupling::DomainScheme> make_paper_domain_scheme(
    const partition::Decomposition& dec, const model::Model& /*model*/,
    const coupling::DomainSchemeOptions& options) {
  return std::make_unique<PaperDomainScheme>(dec, options);
}

}  // namespace crashlink::daemon
