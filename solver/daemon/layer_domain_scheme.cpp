#include "solver/daemon/layer_domain_scheme.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "core/errors.h"
#include "core/log_escape.h"
#include "proto/envelope_name.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_stepper.h"
#include "solver/daemon/apply_setup.h"
#include "solver/daemon/history_row_instants.h"
#include "solver/daemon/layer_wire.h"

namespace crashlink::daemon {

namespace {

class LayerDomainScheme final : public coupling::DomainScheme {
 public:
  LayerDomainScheme(const partition::Decomposition& dec, const model::Model& model,
                    coupling::DomainSchemeOptions o, cosim::LayerForm form)
      : o_(std::move(o)), form_(form), dom_(cosim::build_layer_domain(dec, model, o_.domain)) {
    dom_.solver->set_threads(o_.threads);
  }

  integration::Solver& solver() override { return *dom_.solver; }
  const integration::Solver& solver() const override { return *dom_.solver; }
  coupling::Tick time() const override { return stepper_ ? stepper_->time() : 0; }
  void set_ticks_per_second(std::int64_t tps) override { tps_ = tps; }

  bool uses_lanes() const override { return true; }
  bool lane_message(const wire::Envelope& e) const override {
    return e.has_layer_displacement() || e.has_layer_force();
  }

  std::vector<coupling::LanePartner> lane_partners() const override {
    std::vector<coupling::LanePartner> out;
    for (const auto& port : ports()) out.push_back({port.index, port.partner, port.local.size()});
    return out;
  }

  void fill_register(wire::Register& r) const override {
    const auto& s = *dom_.solver;
    const auto& sub = s.model();
    for (const auto& port : ports()) {
      auto* li = r.add_layer_interfaces();
      li->set_index(port.index);
      li->set_fine_side(port.fine_side);
      for (const auto l : port.local) {
        li->add_j_node_ids(sub.nodes.id[l]);
        li->add_masses_kg(port.fine_side ? 0.0 : s.mass()[l]);
        for (std::size_t d = 0; d < 3; ++d) li->add_positions_m(sub.nodes.x0[3 * l + d]);
      }
    }
  }

  bool start(const wire::Setup& setup) override {
    apply_setup(setup, tps_, o_.domain, dom_.ports);
    stepper_ = std::make_unique<cosim::LayerStepper>(
        *dom_.solver, std::move(dom_.ports), setup.step_ticks(), tps_,
        !setup.variable_steps()            ? cosim::LayerSteps::Fixed
        : setup.mode() == wire::MODE_SPLIT ? cosim::LayerSteps::VariableCommon
                                           : cosim::LayerSteps::Variable);
    stepper_->set_record_history(true);
    if (form_ == cosim::LayerForm::Lts) {
      stepper_->set_form(cosim::LayerForm::Lts, setup.base_ticks());
      if (!setup.variable_steps()) {  // variable steps have no E (it needs one coarse step)
        rows_.emplace(dom_.solver->model().controls.history_interval_s, tps_, setup.base_ticks());
        stepper_->set_lts_energy_wanted([this](coupling::Tick T) { return rows_->reads(T); });
      }
    }
    if (setup.variable_steps())
      stepper_->set_proposal_limits(o_.step_safety, o_.max_step_s);
    else
      stepper_->set_end_time(setup.end_time_ticks());
    return false;
  }

  void initialize() override { stepper_->initialize(); }

  coupling::Pace advance(const std::function<void()>& on_sample, coupling::Tick until) override {
    using Wait = cosim::LayerStepper::Wait;
    Wait w = Wait::None;
    try {
      w = stepper_->advance(on_sample, until);
    } catch (const cosim::LayerPartnerError& x) {
      throw ProtocolError("partner", x.what());
    }
    return w == Wait::Finished ? coupling::Pace::Finished
           : w == Wait::None   ? coupling::Pace::Paused
                               : coupling::Pace::Waiting;
  }

  void drain_outbox(const std::function<void(const coupling::Outgoing&)>& send) override {
    for (const auto& m : stepper_->take_outbox())
      send(coupling::Outgoing{to_envelope(m), static_cast<std::int64_t>(m.interface_index)});
  }

  /// u_J(T + H) leaves before the coarse side's nodal passes, g_A right after the fine side's
  /// (LayerStepper::set_on_outbox).
  void set_on_outbox(std::function<void()> on_outbox) override {
    stepper_->set_on_outbox(std::move(on_outbox));
  }

  void deliver(wire::Envelope&& e) override {
    auto m = to_layer_message(e);
    if (!m) {
      if (e.has_bye()) {
        throw ProtocolError("coordinator",
                            fmt::format("the coordinator ended the session ({}) before domain '{}' "
                                        "reached the end time",
                                        core::log_escape(e.bye().reason()), o_.domain));
      }
      throw ProtocolError("coordinator", fmt::format("unexpected {} during the run of domain '{}'",
                                                     wire::body_name(e), o_.domain));
    }
    try {
      stepper_->deliver(std::move(*m));
    } catch (const ModelError& x) {
      throw ProtocolError("coordinator", x.what());
    }
  }

  /// Progress and the interface history rows completed since the last report (LayerReport).
  std::optional<wire::Envelope> report(bool checkpoint) override {
    if (!stepper_) return std::nullopt;
    wire::Envelope e;
    auto* rep = e.mutable_layer_report();
    rep->set_time_ticks(stepper_->time());
    rep->set_checkpoint(checkpoint);
    for (const auto& h : stepper_->take_history()) {
      auto* rows = rep->add_rows();
      rows->set_interface_index(h.interface_index);
      for (const auto& row : h.rows) {
        rows->add_time_ticks(row.time);
        for (const double f : row.force_N) rows->add_force_n(f);
        rows->add_link_work_j(row.link_work_J);
      }
    }
    return e;
  }

  void fill_bye(wire::DomainReport& /*r*/) const override {}
  bool fields_settled() const override { return !stepper_ || stepper_->rim_settled(); }

  std::pair<double, double> scheme_energy(double instant_s) const override {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (!stepper_ || form_ != cosim::LayerForm::Lts || !rows_) return {nan, nan};
    const coupling::Tick at = rows_->coarse_instant(instant_s);
    const double share = stepper_->lts_energy_at_J(at);
    return {share, std::isfinite(share) ? stepper_->seconds(at) : nan};
  }

  bool at_cycle_boundary() const override { return stepper_->at_cycle_boundary(); }
  coupling::Tick end_time() const override { return stepper_->end_time(); }
  void save_state(core::StateWriter& w) const override { stepper_->save_state(w); }
  void restore_state(const core::StateReader& r) override { stepper_->restore_state(r); }

 private:
  /// The ports: in the domain until start(), in the stepper after.
  const std::vector<cosim::LayerPort>& ports() const {
    return stepper_ ? stepper_->ports() : dom_.ports;
  }

  coupling::DomainSchemeOptions o_;
  cosim::LayerForm form_ = cosim::LayerForm::Layer;
  cosim::LayerDomain dom_;
  std::int64_t tps_ = 0;
  std::optional<HistoryRowInstants> rows_;  ///< lts: the coarse instants the history reads
  std::unique_ptr<cosim::LayerStepper> stepper_;
};

}  // namespace

std::unique_ptr<coupling::DomainScheme> make_layer_domain_scheme(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options) {
  return std::make_unique<LayerDomainScheme>(dec, model, options, cosim::LayerForm::Layer);
}

std::unique_ptr<coupling::DomainScheme> make_lts_domain_scheme(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options) {
  return std::make_unique<LayerDomainScheme>(dec, model, options, cosim::LayerForm::Lts);
}

}  // namespace crashlink::daemon
