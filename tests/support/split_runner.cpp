// SplitRunner: the `layer` scheme's cycle at a common step, all domains in one process
// (split_runner.h; docs/design.md §2.6, §2.7; [1], [2], [8] of Bourel 2005).
#include "tests/support/split_runner.h"

#include <algorithm>
#include <limits>

#include "core/errors.h"

namespace crashlink::cosim {

SplitRunner::SplitRunner(const model::Model& global) : d_(build_layer_domains(global, "split")) {
  std::size_t total_ghosts = 0;
  for (const auto& g : d_.ghosts) total_ghosts = std::max(total_ghosts, g.size());
  u_ghost_.assign(3 * total_ghosts, 0.0);
  build_order();
}

void SplitRunner::build_order() {
  // Kahn's sort of the graph owner -> ghost holder; among the ready solvers the one with the
  // larger step goes first ("coarse first", docs/design.md §2.6), ties by domain order.
  const std::size_t ns = d_.solvers.size();
  std::vector<std::vector<std::size_t>> next(ns);
  std::vector<int> indegree(ns, 0);
  for (std::size_t k = 0; k < ns; ++k) {
    std::vector<std::size_t> owners;
    for (const auto& gl : d_.ghosts[k]) owners.push_back(gl.owner);
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    for (auto o : owners) {
      if (o == k) throw ModelError("split: a domain owns one of its own ghost nodes");
      next[o].push_back(k);
      ++indegree[k];
    }
  }
  auto step_of = [&](std::size_t k) {
    return d_.dec.domain_dt_s[static_cast<std::size_t>(d_.domain_of[k])];
  };
  std::vector<bool> done(ns, false);
  order_.clear();
  while (order_.size() < ns) {
    std::size_t pick = kNoSolver;
    for (std::size_t k = 0; k < ns; ++k)
      if (!done[k] && indegree[k] == 0 && (pick == kNoSolver || step_of(k) > step_of(pick)))
        pick = k;
    if (pick == kNoSolver)
      throw ModelError(
          "split: the domains' ghost owners form a cycle; no processing order "
          "moves every owner before its ghosts");
    done[pick] = true;
    order_.push_back(pick);
    for (auto f : next[pick]) --indegree[f];
  }
}

void SplitRunner::send_coupling_forces() {
  // [8]: J's acceleration is the sum of both sides' forces over J's summed mass (and, for shells,
  // both sides' moments over J's summed rotary inertia).
  for (std::size_t k = 0; k < d_.solvers.size(); ++k) {
    const auto& s = *d_.solvers[k];
    for (const auto& gl : d_.ghosts[k]) {
      d_.solvers[gl.owner]->add_coupling_force(gl.owner_local, s.net_force(gl.local));
      d_.solvers[gl.owner]->add_coupling_moment(gl.owner_local, s.net_moment(gl.local));
    }
  }
}

void SplitRunner::impose_common_step() {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& s : d_.solvers) dt = std::min(dt, s->dt_s());
  dt_ = integration::held_step(dt, dt_);  // as a mono run holds its step
  for (auto& s : d_.solvers) s->impose_step(dt_);
}

void SplitRunner::initialize() {
  for (auto& s : d_.solvers) s->initialize();
  // t = 0 exchange: the fine sides' forces on J at t = 0 added to the owners' a^0
  // (layer_domains.h).
  exchange_initial_forces(d_);
  impose_common_step();
  energy_ = integration::EnergyAccount{};
}

void SplitRunner::begin_cycle() {
  for (auto& s : d_.solvers) s->begin_cycle();
  energy_ = sum_energies(d_, energy_.reference_J);
}

void SplitRunner::end_cycle() {
  for (auto k : order_) {  // coarse first: the owners of k's ghosts have moved already
    auto& s = *d_.solvers[k];
    const auto& gl = d_.ghosts[k];
    if (!gl.empty()) {
      for (std::size_t j = 0; j < gl.size(); ++j) {
        const auto& u = d_.solvers[gl[j].owner]->displacement();
        for (std::size_t d = 0; d < 3; ++d) u_ghost_[3 * j + d] = u[3 * gl[j].owner_local + d];
      }
      s.set_ghost_displacement(u_ghost_.data());
      for (std::size_t j = 0; j < gl.size(); ++j) {  // shell J: the owner's omega^{n+1/2}
        const auto& w = d_.solvers[gl[j].owner]->angular_velocity_mid();
        for (std::size_t d = 0; d < 3; ++d) u_ghost_[3 * j + d] = w[3 * gl[j].owner_local + d];
      }
      s.set_ghost_angular_velocity(u_ghost_.data());
    }
    s.end_cycle_forces();
  }
  send_coupling_forces();
  for (auto& s : d_.solvers) s->end_cycle_accelerations();
  impose_common_step();
}

bool SplitRunner::finished() const {
  return std::all_of(d_.solvers.begin(), d_.solvers.end(),
                     [](const auto& s) { return s->finished(); });
}

double SplitRunner::time_s() const {
  return d_.solvers.empty() ? 0.0 : d_.solvers.front()->time_s();
}

std::int64_t SplitRunner::cycle() const {
  return d_.solvers.empty() ? 0 : d_.solvers.front()->cycle();
}

std::vector<double> SplitRunner::global_displacement() const {
  return cosim::global_displacement(d_);
}

}  // namespace crashlink::cosim
