// LayerNetwork: every domain's LayerStepper in one thread (layer_network.h).
#include "solver/cosim/layer_network.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/errors.h"
#include "core/state_archive.h"
#include "coupling/domain_scheme.h"
#include "coupling/step_policy.h"

namespace crashlink::cosim {

LayerNetwork::LayerNetwork(const model::Model& global, LayerNetworkOptions options)
    : options_(std::move(options)),
      d_(build_layer_domains(global, "layer network",
                             options_.run.scheme == "lts" ? options_.overlap_layers : 0)) {
  if (!(options_.step_safety > 0.0 && options_.step_safety <= 1.0))
    throw ModelError("layer network: step_safety must be in (0, 1], got " +
                     std::to_string(options_.step_safety));
  if (options_.run.ticks_per_second < 1)
    throw ModelError("layer network: ticks_per_second must be >= 1");
  if (options_.run.scheme != "layer" && options_.run.scheme != "lts")
    throw ModelError("layer network: it runs `layer` and `lts`, not '" + options_.run.scheme +
                     "' (cosim::PaperRunner runs `paper` in process)");
  if (options_.run.variable_steps && !options_.proposal_s.empty())
    throw ModelError(
        "layer network: variable steps follow the solvers' own proposals (no proposal_s)");
  if (!options_.proposal_s.empty() && options_.proposal_s.size() != d_.solvers.size())
    throw ModelError("layer network: " + std::to_string(options_.proposal_s.size()) +
                     " step proposals for " + std::to_string(d_.solvers.size()) + " domains");
  std::vector<std::size_t> solver_of(d_.dec.domains.size(), kNoSolver);
  for (std::size_t k = 0; k < d_.domain_of.size(); ++k)
    solver_of[static_cast<std::size_t>(d_.domain_of[k])] = k;
  for (const auto& itf : d_.dec.interfaces) {
    const auto f = solver_of[static_cast<std::size_t>(itf.fine)];
    const auto c = solver_of[static_cast<std::size_t>(itf.coarse)];
    if (f == kNoSolver || c == kNoSolver)
      throw ModelError("layer network: an interface (" + itf.kind + ") joins an empty domain");
    fine_of_.push_back(f);
    coarse_of_.push_back(c);
  }
}

void LayerNetwork::build_steppers() {
  std::vector<Tick> proposal(d_.solvers.size());
  const coupling::TickClock clock(options_.run.ticks_per_second);
  for (std::size_t k = 0; k < d_.solvers.size(); ++k) {
    auto& s = *d_.solvers[k];
    s.initialize();
    // A domain of rigid bodies only has no stable-step limit (proposal 0: follows its partners).
    const double dt = options_.step_safety * s.dt_s();
    const Tick own = std::isfinite(dt) && dt < 1e3 ? clock.step_to_ticks(dt) : 0;
    proposal[k] = own;
    if (!options_.proposal_s.empty() && options_.proposal_s[k] > 0.0)
      proposal[k] = own > 0 ? std::min(own, clock.step_to_ticks(options_.proposal_s[k]))
                            : clock.step_to_ticks(options_.proposal_s[k]);
  }
  std::vector<std::pair<int, int>> links;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < fine_of_.size(); ++i)
    links.emplace_back(static_cast<int>(coarse_of_[i]), static_cast<int>(fine_of_[i]));
  for (const auto& s : d_.solvers) names.push_back(s->domain_name());
  if (options_.run.scheme == "lts" && options_.run.variable_steps && !options_.run.common_step) {
    // the plan is the first owner step: from what the steppers' cost rule sees at t = 0
    // (coordinator::plan_steps alike): the followers' proposals without the step safety
    std::vector<Tick> raw;
    std::vector<double> elements;
    for (const auto& s : d_.solvers) {
      raw.push_back(coupling::own_step_ticks(*s, 0.0, options_.run.ticks_per_second));
      elements.push_back(static_cast<double>(s->model().element_count()));
    }
    proposal = coupling::lts_variable_first_proposals(proposal, raw, links, elements, names);
  }
  plan_ = coupling::nested_steps(proposal, links, options_.run.common_step, names);
  auto ports = layer_ports(d_);
  steppers_.clear();
  for (std::size_t k = 0; k < d_.solvers.size(); ++k) {
    for (auto& p : ports[k])
      if (p.fine_side) p.partner_step = plan_.step[coarse_of_[p.index]];
    steppers_.push_back(std::make_unique<LayerStepper>(
        *d_.solvers[k], std::move(ports[k]), plan_.step[k], options_.run.ticks_per_second,
        !options_.run.variable_steps ? LayerSteps::Fixed
        : options_.run.common_step   ? LayerSteps::VariableCommon
                                     : LayerSteps::Variable));
    if (options_.run.scheme == "lts") steppers_.back()->set_form(LayerForm::Lts, plan_.base);
  }
  if (options_.run.variable_steps) {
    for (auto& st : steppers_) st->set_proposal_limits(options_.step_safety, 0.0);
  } else {  // every domain ends at the same instant, as the coordinator's Setup says
    const Tick end = coupling::aligned_end(plan_, d_.solvers.front()->model().controls.end_time_s,
                                           options_.run.ticks_per_second);
    for (auto& st : steppers_) st->set_end_time(end);
  }
}

double LayerNetwork::lts_energy_J() const {
  double sum = 0.0;
  for (const auto& st : steppers_) {
    if (!st->lts_energy_ready()) return std::numeric_limits<double>::quiet_NaN();
    sum += st->lts_energy_J();
  }
  return sum;
}

void LayerNetwork::initialize() {
  build_steppers();
  for (auto& st : steppers_) st->initialize();
  for (std::size_t k = 0; k < steppers_.size(); ++k) route(k);
}

void LayerNetwork::save_state(std::size_t k, core::StateWriter& w) const {
  d_.solvers[k]->save_state(w);
  steppers_[k]->save_state(w);
}

void LayerNetwork::restore(const std::vector<std::string>& paths) {
  if (paths.size() != d_.solvers.size())
    throw ModelError(fmt::format("layer network: {} checkpoints for {} domains", paths.size(),
                                 d_.solvers.size()));
  build_steppers();
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const core::StateReader r(paths[k]);
    d_.solvers[k]->restore_state(r);
    steppers_[k]->restore_state(r);
  }
}

void LayerNetwork::route(std::size_t from) {
  for (auto& m : steppers_[from]->take_outbox()) {
    const std::size_t to = m.kind == LayerMessage::Kind::Displacement
                               ? fine_of_[m.interface_index]
                               : coarse_of_[m.interface_index];
    steppers_[to]->deliver(std::move(m));
    ++messages_;
  }
}

bool LayerNetwork::run(const std::function<void(std::size_t)>& on_sample, Tick until) {
  using Wait = LayerStepper::Wait;
  // An lts fine side pauses where its owner does, having sent nothing of the next owner step,
  // while the owner needs its Fbar of that instant to get there: the daemons, which write and go
  // on, do it; in one thread the pause would not settle.
  if (options_.run.scheme == "lts" && options_.run.variable_steps &&
      until != std::numeric_limits<Tick>::max())
    throw ModelError(fmt::format(
        "layer network: lts with variable steps does not pause in process (`until` {} ticks); "
        "its checkpoints are the daemons' (crashlink run --checkpoint-interval), or run lts with "
        "fixed steps",
        until));
  for (;;) {
    // The earliest domain that can move goes first (docs/design.md §2.6).
    bool progressed = false, all_done = true, all_paused = true;
    std::vector<std::size_t> order(steppers_.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return steppers_[a]->time() < steppers_[b]->time();
    });
    for (auto k : order) {
      auto& st = *steppers_[k];
      if (st.waiting() == Wait::Finished) continue;
      const Tick t0 = st.time();
      const auto w =
          st.advance(on_sample ? std::function<void()>([&, k] { on_sample(k); }) : nullptr, until);
      if (st.has_outbox()) {
        route(k);
        progressed = true;
      }
      if (st.time() != t0) progressed = true;
      if (w != Wait::Finished) all_done = false;
      if (w != Wait::None && w != Wait::Finished) all_paused = false;
    }
    if (all_done) return true;
    if (all_paused) return false;  // every unfinished domain reached `until`
    if (progressed) continue;
    // A domain paused at `until` while a partner mid-step needs its next message (a coarse step
    // that straddles `until`): the paused domains that a waiting one waits on take one more cycle
    // (only those: in a chain, a domain paused at `until` that nobody waits on stays there).
    std::vector<std::uint8_t> needed(steppers_.size(), 0);
    for (const auto& st : steppers_) {
      const std::uint32_t i = st->waiting_interface();
      if (st->waiting() == Wait::Force) needed[fine_of_[i]] = 1;  // g_A comes from the fine side
      if (st->waiting() == Wait::Displacement) needed[coarse_of_[i]] = 1;
    }
    bool nudged = false;
    for (std::size_t k = 0; k < steppers_.size(); ++k) {
      auto& st = *steppers_[k];
      if (st.waiting() != Wait::None || !needed[k]) continue;
      st.advance(on_sample ? std::function<void()>([&, k] { on_sample(k); }) : nullptr,
                 st.time() + 1);
      route(k);
      nudged = true;
    }
    if (nudged) continue;
    std::string why;
    for (const auto& st : steppers_)
      why += " '" + st->solver().domain_name() + "' at " + std::to_string(st->time()) +
             " ticks waits (" + std::to_string(static_cast<int>(st->waiting())) +
             ") on interface " + std::to_string(st->waiting_interface()) + ";";
    throw ModelError("layer network: no domain can move (internal error, please report):" + why);
  }
}

}  // namespace crashlink::cosim
