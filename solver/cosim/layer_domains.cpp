// Shared pieces of the in-process `layer` runners (layer_domains.h; docs/design.md §2.7).
#include "solver/cosim/layer_domains.h"

#include <algorithm>
#include <string>

#include "core/errors.h"
#include "solver/elements/shell_bt.h"

namespace crashlink::cosim {

namespace {
std::vector<double> natural_inertia(const model::Model& global) {
  std::vector<double> mass(global.nodes.count(), 0.0), inertia(global.nodes.count(), 0.0);
  for (const auto& p : global.parts)
    if (p.kind == model::ElementKind::Shell4)
      elements::shell_lumped_mass(p, global.materials[static_cast<std::size_t>(p.material)],
                                  global.nodes.x0.data(), mass.data(), inertia.data());
  return inertia;
}
}  // namespace

namespace {
/// One domain's solver: ghosts, J's natural summed mass and rotary inertia (§2.7).
std::unique_ptr<integration::Solver> make_solver(const partition::DomainModel& dm,
                                                 const model::Model& global,
                                                 std::vector<double>& inertia_global) {
  auto s = std::make_unique<integration::Solver>(dm.model, dm.name);
  std::vector<std::int32_t> ghosts;
  for (std::size_t l = 0; l < dm.global_node.size(); ++l)
    if (dm.ghost[l]) ghosts.push_back(static_cast<std::int32_t>(l));
  s->set_ghost_nodes(ghosts);
  s->set_mass_override(dm.interface_mass_kg);  // J on its owner: the natural summed mass (§2.7)
  std::vector<double> inertia(dm.global_node.size(), 0.0);  // and its natural rotary inertia
  for (std::size_t l = 0; l < inertia.size(); ++l)
    if (dm.interface_mass_kg[l] > 0.0) {
      if (inertia_global.empty()) inertia_global = natural_inertia(global);
      inertia[l] = inertia_global[static_cast<std::size_t>(dm.global_node[l])];
    }
  s->set_inertia_override(std::move(inertia));
  return s;
}

std::size_t local_of(const partition::DomainModel& dm, std::int32_t g) {
  const auto it = std::lower_bound(dm.global_node.begin(), dm.global_node.end(), g);
  if (it == dm.global_node.end() || *it != g)
    throw ModelError("layer: global node " + std::to_string(g) + " is not in domain '" + dm.name +
                     "'");
  return static_cast<std::size_t>(it - dm.global_node.begin());
}

/// Domain d's ports, from the decomposition alone (J in Interface::j_nodes_global order).
std::vector<LayerPort> ports_of(const partition::Decomposition& dec, int d) {
  std::vector<LayerPort> ports;
  for (std::size_t i = 0; i < dec.interfaces.size(); ++i) {
    const auto& itf = dec.interfaces[i];
    if (itf.fine != d && itf.coarse != d) continue;
    LayerPort p;
    p.index = static_cast<std::uint32_t>(i);
    p.fine_side = itf.fine == d;
    const int other = p.fine_side ? itf.coarse : itf.fine;
    p.partner = dec.domains[static_cast<std::size_t>(other)].name;
    p.partner_elements = dec.domains[static_cast<std::size_t>(other)].model.element_count();
    const auto& dm = dec.domains[static_cast<std::size_t>(d)];
    for (auto g : itf.j_nodes_global) p.local.push_back(local_of(dm, g));
    ports.push_back(std::move(p));
  }
  return ports;
}
}  // namespace

LayerDomains build_layer_domains(const model::Model& global, const char* who, int overlap_layers) {
  LayerDomains r;
  r.dec = partition::decompose(global, partition::Scheme::Layer, overlap_layers);
  const std::size_t ng = global.nodes.count();
  r.owner_solver.assign(ng, kNoSolver);
  r.owner_local.assign(ng, kNoSolver);
  std::vector<double> inertia_global;
  for (std::size_t d = 0; d < r.dec.domains.size(); ++d) {
    const auto& dm = r.dec.domains[d];
    if (dm.empty()) continue;
    const std::size_t k = r.solvers.size();
    for (std::size_t l = 0; l < dm.global_node.size(); ++l) {
      const auto g = static_cast<std::size_t>(dm.global_node[l]);
      if (dm.ghost[l]) continue;
      if (r.owner_solver[g] != kNoSolver)
        throw ModelError(std::string(who) + ": global node id " +
                         std::to_string(global.nodes.id[g]) + " is owned by two domains");
      r.owner_solver[g] = k;
      r.owner_local[g] = l;
    }
    r.solvers.push_back(make_solver(dm, global, inertia_global));
    r.domain_of.push_back(static_cast<int>(d));
  }
  r.ghosts.resize(r.solvers.size());
  for (std::size_t k = 0; k < r.solvers.size(); ++k) {
    const auto& dm = r.dec.domains[static_cast<std::size_t>(r.domain_of[k])];
    for (auto l : r.solvers[k]->ghost_nodes()) {
      const auto lu = static_cast<std::size_t>(l);
      const auto g = static_cast<std::size_t>(dm.global_node[lu]);
      if (r.owner_solver[g] == kNoSolver)
        throw ModelError(std::string(who) + ": ghost node id " +
                         std::to_string(global.nodes.id[g]) + " in domain '" + dm.name +
                         "' has no owner");
      r.ghosts[k].push_back({lu, r.owner_solver[g], r.owner_local[g]});
    }
  }
  return r;
}

LayerDomain build_layer_domain(const partition::Decomposition& dec, const model::Model& global,
                               const std::string& name) {
  for (std::size_t d = 0; d < dec.domains.size(); ++d) {
    const auto& dm = dec.domains[d];
    if (dm.name != name) continue;
    if (dm.empty())
      throw ModelError("layer: domain '" + name +
                       "' is empty after the cut (its elements moved into a finer domain); it "
                       "needs no daemon");
    LayerDomain r;
    r.domain_index = static_cast<int>(d);
    std::vector<double> inertia_global;
    r.solver = make_solver(dm, global, inertia_global);
    r.ports = ports_of(dec, r.domain_index);
    return r;
  }
  std::string known;
  for (const auto& dm : dec.domains) {
    known.append(known.empty() ? "'" : ", '");
    known.append(dm.name);
    known.push_back('\'');
  }
  throw ModelError("layer: no domain named '" + name + "'; the scenario has " + known);
}

std::vector<std::vector<LayerPort>> layer_ports(const LayerDomains& d) {
  std::vector<std::vector<LayerPort>> r;
  for (auto dom : d.domain_of) r.push_back(ports_of(d.dec, dom));
  return r;
}

void exchange_initial_forces(LayerDomains& dm) {
  // Solver::initialize() computed a^0 = M^{-1} f^0 with the owner's forces only; add the ghost
  // holders' forces on J at t = 0 (the implied force M da is the coupling force of t^0).
  const auto& solvers = dm.solvers;
  std::vector<std::vector<double>> df(solvers.size());
  for (std::size_t k = 0; k < solvers.size(); ++k)
    df[k].assign(3 * solvers[k]->model().nodes.count(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < solvers.size(); ++k)
    for (const auto& gl : dm.ghosts[k]) {
      const Vec3 f = solvers[k]->net_force(gl.local);
      for (std::size_t d = 0; d < 3; ++d) {
        df[gl.owner][3 * gl.owner_local + d] += f[d];
        any = any || f[d] != 0.0;
      }
    }
  if (!any) return;
  for (std::size_t k = 0; k < solvers.size(); ++k) {
    auto& s = *solvers[k];
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
}

integration::EnergyAccount sum_energies(const LayerDomains& d, double reference) {
  integration::EnergyAccount e;
  for (const auto& s : d.solvers) e.add_terms(s->energy());
  e.reference_J = reference;
  e.update_reference();
  return e;
}

std::vector<double> global_displacement(const LayerDomains& d) {
  std::vector<double> u(3 * d.owner_solver.size(), 0.0);
  for (std::size_t g = 0; g < d.owner_solver.size(); ++g) {
    if (d.owner_solver[g] == kNoSolver) continue;  // a node no element uses
    const auto& ul = d.solvers[d.owner_solver[g]]->displacement();
    for (std::size_t k = 0; k < 3; ++k) u[3 * g + k] = ul[3 * d.owner_local[g] + k];
  }
  return u;
}

}  // namespace crashlink::cosim
