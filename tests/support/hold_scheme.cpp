// "hold" (tests/support/hold_scheme.h). Its domain side is `paper`'s (free state out, correction
// in: the daemon needs nothing new); its coordinator side below answers the free state of domain k
// at t, once every partner has sent a state at or after t, with
//   a*(t) = sum over the node's copies, in domain order, of the copy's free acceleration at the
//           latest instant <= t of its domain (k's own at t)             ([8] with held values)
// and no drift correction. At equal steps every held value is at t itself, so "hold" is [8]
// exactly; at a step ratio of 2 it differs from `paper`, which interpolates by [10].
#include "tests/support/hold_scheme.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/coordinator_schemes.h"
#include "coordinator/paper_cut.h"
#include "coordinator/paper_exchange.h"
#include "core/errors.h"
#include "solver/daemon/domain_schemes.h"
#include "solver/daemon/paper_domain_scheme.h"
#include "solver/partition/decomposition.h"

namespace crashlink::test_schemes {

namespace {

class HoldCoordinatorScheme final : public coordinator::CoordinatorScheme {
 public:
  HoldCoordinatorScheme(const model::Model& model, const coordinator::CoordinatorOptions& o)
      : o_(o),
        cut_(coordinator::paper_cut(model, partition::decompose(model, partition::Scheme::Paper))) {
  }

  const coordinator::LayerCut& cut() const override { return cut_.cut; }

  void check_register(int k, const wire::Register& r) const override {
    coordinator::check_paper_register(cut_, k, r);
  }

  void start(const std::vector<wire::Register>& regs, const wire::Options& options,
             coordinator::CoordinatorPort& port) override {
    table_ = coordinator::match_paper(cut_, regs);
    plan_ = coordinator::plan_steps(cut_.cut, regs, o_.run.common_step);
    end_ = coordinator::paper_end_ticks(cut_.cut.end_time_s, plan_.step, o_.run.ticks_per_second);
    const auto n = cut_.cut.names.size();
    states_.resize(n);
    latest_.assign(n, -1);
    waiting_.assign(n, false);
    finished_.assign(n, false);
    for (std::size_t k = 0; k < n; ++k)
      port.send(
          static_cast<int>(k),
          coordinator::paper_setup(cut_, table_, plan_, static_cast<int>(k), o_.run.common_step,
                                   options, o_.run.ticks_per_second, end_));
  }

  bool receive(int k, const wire::Envelope& e, coordinator::CoordinatorPort& port) override {
    if (!e.has_free_state()) return false;
    const auto ku = static_cast<std::size_t>(k);
    const auto& f = e.free_state();
    if (waiting_[ku] || finished_[ku] || f.time_ticks() <= latest_[ku])
      throw ProtocolError(fmt::format("domain '{}' sent a free state at tick {} out of turn",
                                      cut_.cut.names[ku], f.time_ticks()));
    states_[ku].push_back(
        {f.time_ticks(), {f.accelerations_m_s2().begin(), f.accelerations_m_s2().end()}});
    latest_[ku] = f.time_ticks();
    waiting_[ku] = true;
    answer(port);
    return true;
  }

  void bye(int k, const wire::Bye& /*b*/, coordinator::CoordinatorPort& /*port*/) override {
    if (!finished_[static_cast<std::size_t>(k)])
      throw ProtocolError("a Bye before the stop of a `hold` run");
  }

  coupling::Tick reached(int k) const override {
    return std::max<coupling::Tick>(latest_[static_cast<std::size_t>(k)], 0);
  }
  coupling::Tick step(int k) const override { return plan_.step[static_cast<std::size_t>(k)]; }
  void fill_result(coordinator::CoordinatorResult& /*r*/) const override {}
  double cpu_before() const override { return 0.0; }

 private:
  struct State {
    coupling::Tick time = 0;
    std::vector<double> a;  ///< free accelerations, Register order
  };

  /// Every waiting state whose partners have all sent a state at or after it, answered.
  void answer(coordinator::CoordinatorPort& port) {
    for (bool progress = true; progress;) {
      progress = false;
      for (std::size_t k = 0; k < states_.size(); ++k) {
        if (!waiting_[k]) continue;
        const coupling::Tick t = latest_[k];
        bool ready = true;
        for (std::size_t d = 0; d < states_.size(); ++d)
          ready = ready && (d == k || finished_[d] || latest_[d] >= t);
        if (!ready) continue;
        port.send(static_cast<int>(k), correction(k, t));
        waiting_[k] = false;
        finished_[k] = t >= end_;
        progress = true;
      }
    }
  }

  /// Domain d's free acceleration of its node `local` at its latest instant <= t (held).
  double held(std::size_t d, std::int32_t local, std::size_t xyz, coupling::Tick t) const {
    for (auto it = states_[d].rbegin(); it != states_[d].rend(); ++it)
      if (it->time <= t) return it->a[3 * static_cast<std::size_t>(local) + xyz];
    throw ModelError("hold: no state at or before the instant");
  }

  wire::Envelope correction(std::size_t k, coupling::Tick t) const {
    wire::Envelope e;
    auto* c = e.mutable_correction();
    c->set_time_ticks(t);
    const bool stop = t >= end_;
    c->set_stop(stop);
    const auto h = stop ? 0 : plan_.step[k];
    c->set_imposed_step_ticks(h);
    c->set_imposed_step_s(static_cast<double>(h) / static_cast<double>(o_.run.ticks_per_second));
    for (const auto node : table_.node_of[k]) {
      const auto& copies = table_.nodes[static_cast<std::size_t>(node)].copies;
      for (std::size_t xyz = 0; xyz < 3; ++xyz) {
        // [8] in domain order, the first copy's value first (link_acceleration's order).
        double a =
            held(static_cast<std::size_t>(copies.front().domain), copies.front().local, xyz, t);
        for (std::size_t i = 1; i < copies.size(); ++i)
          a += held(static_cast<std::size_t>(copies[i].domain), copies[i].local, xyz, t);
        c->add_accelerations_m_s2(a);
      }
    }
    return e;
  }

  const coordinator::CoordinatorOptions& o_;
  coordinator::PaperCut cut_;
  coupling::InterfaceTable table_;
  coupling::StepPlan plan_;
  coupling::Tick end_ = 0;
  std::vector<std::deque<State>> states_;  ///< [domains] every free state (a short test run)
  std::vector<coupling::Tick> latest_;     ///< [domains] the instant of the newest state
  std::vector<bool> waiting_, finished_;
};

}  // namespace

void register_hold() {
  static const bool once = [] {
    daemon::register_domain_scheme(
        {"hold", partition::Scheme::Paper, daemon::make_paper_domain_scheme});
    coordinator::register_coordinator_scheme(
        {"hold",
         [](const model::Model& m, const coordinator::CoordinatorOptions& o)
             -> std::unique_ptr<coordinator::CoordinatorScheme> {
           return std::make_unique<HoldCoordinatorScheme>(m, o);
         }});
    return true;
  }();
  (void)once;
}

}  // namespace crashlink::test_schemes
