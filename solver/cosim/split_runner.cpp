// SplitRunner: the `layer` scheme's cycle at a common step, all domains in one process
// (split_runner.h; DESIGN.md §2.6, §2.7; [1], [2], [8] of Bourel 2005).
#include "solver/cosim/split_runner.h"

#include <algorithm>
#include <limits>
#include <string>

#include "solver/core/errors.h"
#include "solver/elements/shell_bt.h"

namespace crashlink::cosim {

namespace {
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
}

const std::vector<double>& SplitRunner::natural_inertia() {
  if (inertia_.empty()) {
    std::vector<double> mass(global_.nodes.count(), 0.0);
    inertia_.assign(global_.nodes.count(), 0.0);
    for (const auto& p : global_.parts)
      if (p.kind == model::ElementKind::Shell4)
        elements::shell_lumped_mass(p, global_.materials[static_cast<std::size_t>(p.material)],
                                    global_.nodes.x0.data(), mass.data(), inertia_.data());
  }
  return inertia_;
}

SplitRunner::SplitRunner(const model::Model& global)
    : global_(global), dec_(partition::decompose(global, partition::Scheme::Layer)) {
  const std::size_t ng = global_.nodes.count();
  owner_solver_.assign(ng, kNone);
  owner_local_.assign(ng, kNone);
  for (std::size_t d = 0; d < dec_.domains.size(); ++d) {
    const auto& dm = dec_.domains[d];
    if (dm.empty()) continue;
    const std::size_t k = solvers_.size();
    auto s = std::make_unique<integration::Solver>(dm.model, dm.name);
    std::vector<std::int32_t> ghosts;
    for (std::size_t l = 0; l < dm.global_node.size(); ++l) {
      const auto g = static_cast<std::size_t>(dm.global_node[l]);
      if (dm.ghost[l]) {
        ghosts.push_back(static_cast<std::int32_t>(l));
        continue;
      }
      if (owner_solver_[g] != kNone)
        throw ModelError("split: global node id " + std::to_string(global_.nodes.id[g]) +
                         " is owned by two domains");
      owner_solver_[g] = k;
      owner_local_[g] = l;
    }
    s->set_ghost_nodes(ghosts);
    s->set_mass_override(dm.interface_mass_kg);  // J on its owner: the natural summed mass (§2.7)
    {  // and, for shells, its natural summed rotary inertia
      std::vector<double> inertia(dm.global_node.size(), 0.0);
      for (std::size_t l = 0; l < inertia.size(); ++l)
        if (dm.interface_mass_kg[l] > 0.0)
          inertia[l] = natural_inertia()[static_cast<std::size_t>(dm.global_node[l])];
      s->set_inertia_override(std::move(inertia));
    }
    solvers_.push_back(std::move(s));
    domain_of_.push_back(static_cast<int>(d));
  }
  ghosts_.resize(solvers_.size());
  std::size_t total_ghosts = 0;
  for (std::size_t k = 0; k < solvers_.size(); ++k) {
    const auto& dm = dec_.domains[static_cast<std::size_t>(domain_of_[k])];
    for (auto l : solvers_[k]->ghost_nodes()) {
      const auto lu = static_cast<std::size_t>(l);
      const auto g = static_cast<std::size_t>(dm.global_node[lu]);
      if (owner_solver_[g] == kNone)
        throw ModelError("split: ghost node id " + std::to_string(global_.nodes.id[g]) +
                         " in domain '" + dm.name + "' has no owner");
      ghosts_[k].push_back({lu, owner_solver_[g], owner_local_[g]});
    }
    total_ghosts = std::max(total_ghosts, ghosts_[k].size());
  }
  u_ghost_.assign(3 * total_ghosts, 0.0);
  build_order();
}

void SplitRunner::build_order() {
  // Kahn's sort of the graph owner -> ghost holder; among the ready solvers the one with the
  // larger step goes first ("coarse first", DESIGN.md §2.6), ties by domain order.
  const std::size_t ns = solvers_.size();
  std::vector<std::vector<std::size_t>> next(ns);
  std::vector<int> indegree(ns, 0);
  for (std::size_t k = 0; k < ns; ++k) {
    std::vector<std::size_t> owners;
    for (const auto& gl : ghosts_[k]) owners.push_back(gl.owner);
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    for (auto o : owners) {
      if (o == k) throw ModelError("split: a domain owns one of its own ghost nodes");
      next[o].push_back(k);
      ++indegree[k];
    }
  }
  auto step_of = [&](std::size_t k) {
    return dec_.domain_dt_s[static_cast<std::size_t>(domain_of_[k])];
  };
  std::vector<bool> done(ns, false);
  order_.clear();
  while (order_.size() < ns) {
    std::size_t pick = kNone;
    for (std::size_t k = 0; k < ns; ++k)
      if (!done[k] && indegree[k] == 0 && (pick == kNone || step_of(k) > step_of(pick))) pick = k;
    if (pick == kNone)
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
  for (std::size_t k = 0; k < solvers_.size(); ++k) {
    const auto& s = *solvers_[k];
    for (const auto& gl : ghosts_[k]) {
      solvers_[gl.owner]->add_coupling_force(gl.owner_local, s.net_force(gl.local));
      solvers_[gl.owner]->add_coupling_moment(gl.owner_local, s.net_moment(gl.local));
    }
  }
}

void SplitRunner::impose_common_step() {
  dt_ = std::numeric_limits<double>::infinity();
  for (const auto& s : solvers_) dt_ = std::min(dt_, s->dt_s());
  for (auto& s : solvers_) s->impose_step(dt_);
}

void SplitRunner::initialize() {
  for (auto& s : solvers_) s->initialize();
  // t = 0 exchange: Solver::initialize() computed a^0 = M^{-1} f^0 with the owner's forces only;
  // add the fine sides' forces on J at t = 0 through set_acceleration (its implied force M da is
  // held as the coupling force of t^0 and counted as coupling work over the first step).
  std::vector<std::vector<double>> df(solvers_.size());
  for (std::size_t k = 0; k < solvers_.size(); ++k)
    df[k].assign(3 * solvers_[k]->model().nodes.count(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < solvers_.size(); ++k) {
    const auto& s = *solvers_[k];
    for (const auto& gl : ghosts_[k]) {
      const Vec3 f = s.net_force(gl.local);
      for (std::size_t d = 0; d < 3; ++d) {
        const double fd = f[d];
        df[gl.owner][3 * gl.owner_local + d] += fd;
        any = any || fd != 0.0;
      }
    }
  }
  if (any)
    for (std::size_t k = 0; k < solvers_.size(); ++k) {
      auto& s = *solvers_[k];
      const auto& fixed = s.model().fixed;
      for (std::size_t i = 0; i < s.model().nodes.count(); ++i) {
        const double* f = &df[k][3 * i];
        if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) continue;
        Vec3 a{};
        for (std::size_t d = 0; d < 3; ++d) {
          a[d] = s.acceleration()[3 * i + d] + f[d] / s.mass()[i];
          if (!fixed.empty() && (fixed[i] & (1u << d))) a[d] = 0.0;
        }
        s.set_acceleration(i, a);
      }
    }
  impose_common_step();
  energy_ = integration::EnergyAccount{};
}

void SplitRunner::begin_cycle() {
  for (auto& s : solvers_) s->begin_cycle();
  sum_energies();
}

void SplitRunner::end_cycle() {
  for (auto k : order_) {  // coarse first: the owners of k's ghosts have moved already
    auto& s = *solvers_[k];
    const auto& gl = ghosts_[k];
    if (!gl.empty()) {
      for (std::size_t j = 0; j < gl.size(); ++j) {
        const auto& u = solvers_[gl[j].owner]->displacement();
        for (std::size_t d = 0; d < 3; ++d) u_ghost_[3 * j + d] = u[3 * gl[j].owner_local + d];
      }
      s.set_ghost_displacement(u_ghost_.data());
      for (std::size_t j = 0; j < gl.size(); ++j) {  // shell J: the owner's omega^{n+1/2}
        const auto& w = solvers_[gl[j].owner]->angular_velocity_mid();
        for (std::size_t d = 0; d < 3; ++d) u_ghost_[3 * j + d] = w[3 * gl[j].owner_local + d];
      }
      s.set_ghost_angular_velocity(u_ghost_.data());
    }
    s.end_cycle_forces();
  }
  send_coupling_forces();
  for (auto& s : solvers_) s->end_cycle_accelerations();
  impose_common_step();
}

bool SplitRunner::finished() const {
  return std::all_of(solvers_.begin(), solvers_.end(), [](const auto& s) { return s->finished(); });
}

double SplitRunner::time_s() const {
  return solvers_.empty() ? 0.0 : solvers_.front()->time_s();
}

std::int64_t SplitRunner::cycle() const {
  return solvers_.empty() ? 0 : solvers_.front()->cycle();
}

std::vector<double> SplitRunner::global_displacement() const {
  std::vector<double> u(3 * global_.nodes.count(), 0.0);
  for (std::size_t g = 0; g < owner_solver_.size(); ++g) {
    if (owner_solver_[g] == kNone) continue;  // a node no element uses
    const auto& ul = solvers_[owner_solver_[g]]->displacement();
    for (std::size_t d = 0; d < 3; ++d) u[3 * g + d] = ul[3 * owner_local_[g] + d];
  }
  return u;
}

void SplitRunner::sum_energies() {
  const double reference = energy_.reference_J;
  integration::EnergyAccount e;
  for (const auto& s : solvers_) {
    const auto& x = s->energy();
    e.kinetic_J += x.kinetic_J;
    e.internal_J += x.internal_J;
    e.hourglass_J += x.hourglass_J;
    e.contact_J += x.contact_J;
    e.external_work_J += x.external_work_J;
    e.coupling_work_J += x.coupling_work_J;
    e.initial_total_J += x.initial_total_J;
  }
  e.reference_J = reference;
  e.update_reference();
  energy_ = e;
}

}  // namespace crashlink::cosim
