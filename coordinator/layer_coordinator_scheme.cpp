#include "coordinator/layer_coordinator_scheme.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <span>
#include <utility>

#include "coordinator/coordinator_checkpoints.h"
#include "coordinator/coupling_history.h"
#include "core/errors.h"
#include "coupling/coupling_config.h"
#include "coupling/layer_router.h"
#include "solver/partition/decomposition.h"

namespace crashlink::coordinator {

namespace {

std::span<const double> view(const google::protobuf::RepeatedField<double>& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

class LayerCoordinatorScheme final : public CoordinatorScheme {
 public:
  LayerCoordinatorScheme(const model::Model& model, const CoordinatorOptions& o,
                         std::string scheme = "layer")
      : o_(o), scheme_(std::move(scheme)) {
    const int overlap = scheme_ == "lts" ? coupling::kLtsOverlapLayers : 0;
    cut_ = layer_cut(model, partition::decompose(model, partition::Scheme::Layer, overlap));
    latest_.assign(cut_.names.size(), 0);
    step_.assign(cut_.names.size(), 0);
  }

  const LayerCut& cut() const override { return cut_; }

  void check_register(int k, const wire::Register& r) const override {
    coordinator::check_register(cut_, k, r);
  }

  void start(const std::vector<wire::Register>& regs, const wire::Options& base,
             CoordinatorPort& port) override {
    match_sides(cut_, regs);
    const auto plan =
        plan_steps(cut_, regs, o_.run.common_step,
                   scheme_ == "lts" && o_.run.variable_steps ? o_.run.ticks_per_second : 0);
    step_ = plan.step;
    std::vector<coupling::LayerRoute> routes;
    for (const auto& c : cut_.interfaces) {
      const auto H = plan.step[static_cast<std::size_t>(c.coarse)];
      routes.push_back({c.fine, c.coarse, c.j_node_ids.size(), H,
                        static_cast<double>(H) / static_cast<double>(o_.run.ticks_per_second)});
    }
    router_ = std::make_unique<coupling::LayerRouter>(std::move(routes), cut_.names);
    router_->set_variable_steps(o_.run.variable_steps);
    lanes_ = o_.run.lanes && std::all_of(regs.begin(), regs.end(), [](const wire::Register& r) {
               return !r.lane_endpoint().empty();
             });
    auto& checkpoints = port.checkpoints();
    wire::Options options = base;
    options.set_checkpoint_interval_ticks(checkpoints.plan(plan.step));
    if (o_.run.restart) {
      const auto T = checkpoints.choose_restart(regs, router_->size() > 0);
      cpu_before_ = checkpoints.restore(T, *router_, port.history());
      if (router_->size() > 0) std::fill(latest_.begin(), latest_.end(), T);
    }
    const coupling::Tick restart_from = checkpoints.restarted_from();
    for (std::size_t k = 0; k < cut_.names.size(); ++k) {
      auto setup = setup_message(cut_, plan, static_cast<int>(k), o_.run.common_step, options,
                                 o_.run.ticks_per_second, scheme_);
      setup.mutable_setup()->set_variable_steps(o_.run.variable_steps);
      if (restart_from >= 0) {
        setup.mutable_setup()->set_restart(true);
        setup.mutable_setup()->set_restart_ticks(restart_from);
      }
      if (lanes_) add_lanes(static_cast<int>(k), regs, *setup.mutable_setup());
      port.send(static_cast<int>(k), setup);
    }
    std::string steps;
    for (std::size_t k = 0; k < cut_.names.size(); ++k) {
      steps += fmt::format(
          "{}{} {:.4e} s", k == 0 ? "" : ", ", cut_.names[k],
          static_cast<double>(plan.step[k]) / static_cast<double>(o_.run.ticks_per_second));
    }
    port.log(fmt::format(
        "{} run, {}: {}; layer vectors {}", o_.run.common_step ? "split" : "multi",
        o_.run.variable_steps ? "variable steps (each its own proposal), planned first" : "steps",
        steps, lanes_ ? "daemon to daemon (lanes)" : "through the coordinator"));
  }

  bool receive(int k, const wire::Envelope& e, CoordinatorPort& port) override {
    if (e.has_layer_report()) {
      report(k, e.layer_report(), port);
    } else if (e.has_layer_force()) {
      const auto& f = e.layer_force();
      const auto routed = router_->force(k, f.interface_index(), f.time_ticks(), view(f.forces_n()),
                                         view(f.moments_n_m()));
      port.forward_current(routed.to);
    } else if (e.has_layer_displacement()) {
      const auto& d = e.layer_displacement();
      const auto routed =
          router_->displacement(k, d.interface_index(), d.time_ticks(), view(d.displacements_m()),
                                view(d.angular_velocities_rad_s()));
      port.forward_current(routed.to);
    } else {
      return false;
    }
    return true;
  }

  void bye(int /*k*/, const wire::Bye& /*b*/, CoordinatorPort& /*port*/) override {}

  coupling::Tick reached(int k) const override { return latest_[static_cast<std::size_t>(k)]; }
  coupling::Tick step(int k) const override { return step_[static_cast<std::size_t>(k)]; }

  void fill_result(CoordinatorResult& r) const override {
    r.messages_forwarded = router_ ? router_->forwarded() : 0;
    r.lanes = lanes_;
    r.reports = reports_;
  }

  double cpu_before() const override { return cpu_before_; }

 private:
  /// A LayerReport from domain k: its progress and, from a fine side, history rows, each checked
  /// (LayerRouter::rows: k's fine-side interface, the next owner instants in order, sizes).
  void report(int k, const wire::LayerReport& rep, CoordinatorPort& port) {
    ++reports_;
    const auto ku = static_cast<std::size_t>(k);
    if (rep.time_ticks() < latest_[ku]) {
      throw ProtocolError(
          fmt::format("domain '{}' reported t = {} ticks after t = {} ticks (time goes forward)",
                      cut_.names[ku], rep.time_ticks(), latest_[ku]));
    }
    latest_[ku] = rep.time_ticks();
    // At the end time the daemon writes its results before its Bye.
    if (static_cast<double>(rep.time_ticks()) >=
        cut_.end_time_s * static_cast<double>(o_.run.ticks_per_second) - 0.5)
      port.allow_silence(k);
    for (const auto& rows : rep.rows()) {
      const auto i = rows.interface_index();
      const auto samples = router_->rows(
          k, i, {rows.time_ticks().data(), static_cast<std::size_t>(rows.time_ticks_size())},
          view(rows.force_n()), view(rows.link_work_j()));
      port.history().append(i, samples, o_.run.ticks_per_second);
      if (!samples.empty()) port.checkpoints().rows_reached(i, samples.back().time);
    }
    if (rep.checkpoint()) port.checkpoints().announced(rep.time_ticks());
    port.checkpoints().write_when_complete(*router_, port.history(), port.cpu_seconds());
  }

  /// A partner's lane in daemon k's Setup for every domain k shares an interface with.
  void add_lanes(int k, const std::vector<wire::Register>& regs, wire::Setup& setup) const {
    std::set<int> partners;
    for (const auto& c : cut_.interfaces) {
      if (c.fine == k) partners.insert(c.coarse);
      if (c.coarse == k) partners.insert(c.fine);
    }
    for (const int p : partners) {
      auto* lane = setup.add_lanes();
      lane->set_domain(cut_.names[static_cast<std::size_t>(p)]);
      lane->set_endpoint(regs[static_cast<std::size_t>(p)].lane_endpoint());
      lane->set_public_key(regs[static_cast<std::size_t>(p)].lane_public_key());
    }
  }

  const CoordinatorOptions& o_;
  std::string scheme_;  ///< "layer" or "lts"
  LayerCut cut_;
  std::vector<coupling::Tick> latest_;  ///< [daemons] the instant of the latest report
  std::vector<coupling::Tick> step_;    ///< [daemons] the planned steps
  std::unique_ptr<coupling::LayerRouter> router_;
  bool lanes_ = false;
  std::int64_t reports_ = 0;
  double cpu_before_ = 0.0;
};

}  // namespace

void validate_layer_config(const coupling::CouplingConfig& config) {
  if (!config.drift)
    throw InputError(
        "--no-drift: a `paper` option; `layer` has no drift correction (add --coupling paper, "
        "or drop the option)");
}

std::unique_ptr<CoordinatorScheme> make_layer_coordinator_scheme(
    const model::Model& model, const CoordinatorOptions& options) {
  return std::make_unique<LayerCoordinatorScheme>(model, options);
}

void validate_lts_config(const coupling::CouplingConfig& config) {
  if (!config.drift)
    throw InputError(
        "--no-drift: a `paper` option; `lts` has no drift correction (add --coupling paper, "
        "or drop the option)");
  if (config.variable_steps && config.common_step)
    throw InputError(
        "--mode split --variable-steps with --coupling lts: one common step is `layer`'s split "
        "(lts at one step is `layer`); drop --coupling lts, or run --mode multi");
}

std::unique_ptr<CoordinatorScheme> make_lts_coordinator_scheme(const model::Model& model,
                                                               const CoordinatorOptions& options) {
  return std::make_unique<LayerCoordinatorScheme>(model, options, "lts");
}

}  // namespace crashlink::coordinator
