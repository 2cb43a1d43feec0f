#include "coordinator/paper_coordinator_scheme.h"

#include <fmt/format.h>

#include <utility>

#include "coordinator/coupling_history.h"
#include "coordinator/paper_cut.h"
#include "coordinator/paper_exchange.h"
#include "core/errors.h"
#include "core/log_escape.h"
#include "solver/partition/decomposition.h"

namespace crashlink::coordinator {

namespace {

class PaperCoordinatorScheme final : public CoordinatorScheme {
 public:
  PaperCoordinatorScheme(const model::Model& model, const CoordinatorOptions& o) : o_(o) {
    cut_ = paper_cut(model, partition::decompose(model, partition::Scheme::Paper));
    step_.assign(cut_.cut.names.size(), 0);
  }

  const LayerCut& cut() const override { return cut_.cut; }

  void check_register(int k, const wire::Register& r) const override {
    check_paper_register(cut_, k, r);
  }

  /// The exchange, the Setups (summed masses, roles, step) and the log line.
  void start(const std::vector<wire::Register>& regs, const wire::Options& base,
             CoordinatorPort& port) override {
    const auto table = match_paper(cut_, regs);
    const auto plan = plan_steps(cut_.cut, regs, o_.run.common_step);
    step_ = plan.step;
    wire::Options options = base;
    options.set_drift_correction(o_.run.drift);
    exchange_ = std::make_unique<PaperExchange>(
        cut_, table, plan.step,
        o_.run.drift ? coupling::paper::Drift::on : coupling::paper::Drift::off, o_.run.guard_rise,
        o_.run.ticks_per_second,
        !o_.run.variable_steps ? PaperExchange::Steps::fixed
        : o_.run.common_step   ? PaperExchange::Steps::variable_common
                               : PaperExchange::Steps::variable_own);
    const auto& names = cut_.cut.names;
    std::string steps;
    for (std::size_t k = 0; k < names.size(); ++k) {
      port.send(static_cast<int>(k),
                paper_setup(cut_, table, plan, static_cast<int>(k), o_.run.common_step, options,
                            o_.run.ticks_per_second, exchange_->end_ticks()));
      steps += fmt::format(
          "{}{} {:.4e} s", k == 0 ? "" : ", ", names[k],
          static_cast<double>(plan.step[k]) / static_cast<double>(o_.run.ticks_per_second));
    }
    port.log(fmt::format(
        "{} run, scheme `paper` (drift correction [11] {}, {} coupled nodes), {}: {}",
        o_.run.common_step ? "split" : "multi", o_.run.drift ? "on" : "off", table.nodes.size(),
        o_.run.variable_steps ? "variable steps (each state's proposal), initially" : "steps",
        steps));
  }

  /// Domain k's free state in, the corrections it allows out, the rows it completes.
  bool receive(int k, const wire::Envelope& e, CoordinatorPort& port) override {
    if (!e.has_free_state()) return false;
    try {
      exchange_->submit(k, e.free_state());
      while (auto c = exchange_->next()) port.send(c->first, c->second);
    } catch (...) {
      port.history().append(exchange_->take_rows(), o_.run.ticks_per_second);  // what was complete
      throw;
    }
    port.history().append(exchange_->take_rows(), o_.run.ticks_per_second);
    return true;
  }

  /// A Bye before the stop would leave its partners waiting for its states.
  void bye(int k, const wire::Bye& b, CoordinatorPort& /*port*/) override {
    if (!exchange_->finished(k))
      throw ProtocolError(
          fmt::format("domain '{}' said Bye ({}) at tick {} before the end of the "
                      "`paper` run",
                      cut_.cut.names[static_cast<std::size_t>(k)], core::log_escape(b.reason()),
                      exchange_->latest(k)));
    exchange_->final_energy(k, b.report().energy(), b.report().time_ticks());
  }

  coupling::Tick reached(int k) const override { return exchange_ ? exchange_->latest(k) : 0; }
  coupling::Tick step(int k) const override { return step_[static_cast<std::size_t>(k)]; }
  void fill_result(CoordinatorResult& /*r*/) const override {}
  double cpu_before() const override { return 0.0; }

 private:
  const CoordinatorOptions& o_;
  PaperCut cut_;
  std::vector<coupling::Tick> step_;
  std::unique_ptr<PaperExchange> exchange_;
};

}  // namespace

void validate_paper_config(const coupling::CouplingConfig& config) {
  if (config.checkpoint_interval_s > 0.0 || config.restart)
    throw InputError(
        "--coupling paper: checkpoints and --restart are features of `layer` "
        "runs; run `paper` without them");
}

std::unique_ptr<CoordinatorScheme> make_paper_coordinator_scheme(
    const model::Model& model, const CoordinatorOptions& options) {
  return std::make_unique<PaperCoordinatorScheme>(model, options);
}

}  // namespace crashlink::coordinator
