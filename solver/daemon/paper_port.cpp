// One domain of a `paper` run as its daemon sees it (paper_port.h).
#include "solver/daemon/paper_port.h"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "transport/errors.h"

namespace crashlink::daemon {

PaperPort build_paper_port(const partition::Decomposition& dec, const std::string& name) {
  int d = -1;
  for (std::size_t i = 0; i < dec.domains.size(); ++i)
    if (dec.domains[i].name == name) d = static_cast<int>(i);
  if (d < 0 || dec.domains[static_cast<std::size_t>(d)].empty())
    throw ModelError(fmt::format("the scenario's `paper` cut has no non-empty domain '{}'", name));
  PaperPort p;
  p.domain = &dec.domains[static_cast<std::size_t>(d)];
  p.nodes = cosim::paper_nodes(dec, d);
  cosim::refuse_rotations_on_both_sides(dec, d, p.nodes);
  std::vector<double> mass, inertia;
  cosim::partial_masses(p.domain->model, mass, inertia);
  for (const auto& n : p.nodes) {
    p.own_mass_kg.push_back(n.copy ? 0.0 : mass[n.local]);
    p.summed_mass_kg.push_back(p.domain->interface_mass_kg[n.local]);
    if (n.reference) p.reference.push_back(n.local);
  }
  std::vector<double> override(p.domain->global_node.size(), 0.0);
  for (std::size_t j = 0; j < p.nodes.size(); ++j) override[p.nodes[j].local] = p.summed_mass_kg[j];
  p.solver = std::make_unique<integration::Solver>(p.domain->model, name);
  p.solver->set_mass_override(std::move(override));
  return p;
}

std::unique_ptr<integration::Solver> use_summed_masses(PaperPort& port, const wire::Setup& setup,
                                                       const std::string& domain) {
  const auto n = port.nodes.size();
  if (static_cast<std::size_t>(setup.summed_masses_kg_size()) != n ||
      static_cast<std::size_t>(setup.node_roles_size()) != n)
    throw ProtocolError(
        "coordinator",
        fmt::format("the `paper` Setup of domain '{}' has {} summed masses and {} "
                    "roles for its {} coupled nodes",
                    domain, setup.summed_masses_kg_size(), setup.node_roles_size(), n));
  bool differs = false;
  for (std::size_t j = 0; j < n; ++j) {
    const auto& node = port.nodes[j];
    const double M = setup.summed_masses_kg(static_cast<int>(j));
    const double natural = port.summed_mass_kg[j];
    const auto role = setup.node_roles(static_cast<int>(j));
    const bool ref = role == wire::NODE_ROLE_REFERENCE;
    const auto id = port.domain->model.nodes.id[node.local];
    if (ref != node.reference ||
        (role != wire::NODE_ROLE_REFERENCE && role != wire::NODE_ROLE_NON_REFERENCE))
      throw ProtocolError("coordinator",
                          fmt::format("the `paper` Setup of domain '{}' gives node id {} the role "
                                      "{}; this domain's cut makes it {}",
                                      domain, id, wire::NodeRole_Name(role),
                                      node.reference ? "the reference" : "the non-reference side"));
    if (!(std::abs(M - natural) <= 1e-12 * natural))
      throw ProtocolError(
          "coordinator",
          fmt::format("the `paper` Setup of domain '{}' gives node id {} the summed mass {} kg; "
                      "the cut's natural mass is {} kg (is the node used by a third domain, or "
                      "did the coordinator read another scenario?)",
                      domain, id, M, natural));
    differs = differs || M != natural;
    port.summed_mass_kg[j] = M;
  }
  if (!differs) return nullptr;
  std::vector<double> override(port.domain->global_node.size(), 0.0);
  for (std::size_t j = 0; j < n; ++j) override[port.nodes[j].local] = port.summed_mass_kg[j];
  auto fresh = std::make_unique<integration::Solver>(port.domain->model, domain);
  fresh->set_mass_override(std::move(override));
  return fresh;
}

void fill_free_state(const PaperPort& port, std::int64_t time_ticks, std::int64_t stable_step_ticks,
                     const wire::EnergyTerms& energy, std::int64_t energy_time_ticks,
                     wire::Envelope& out) {
  const auto& s = *port.solver;
  auto* f = out.mutable_free_state();
  f->set_time_ticks(time_ticks);
  f->set_cycle(s.cycle());
  const std::size_t n3 = 3 * port.nodes.size();
  auto* a = f->mutable_accelerations_m_s2();
  auto* u = f->mutable_displacements_m();
  auto* v = f->mutable_velocities_m_s();
  a->Clear();  // keeps the capacity
  u->Clear();
  v->Clear();
  a->Reserve(static_cast<int>(n3));
  u->Reserve(static_cast<int>(n3));
  v->Reserve(static_cast<int>(n3));
  for (const auto& n : port.nodes)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * n.local + d;
      a->Add(s.acceleration()[k]);
      u->Add(s.displacement()[k]);
      v->Add(s.velocity_mid()[k]);
    }
  f->set_stable_step_ticks(stable_step_ticks);
  f->set_stable_step_s(s.dt_s());
  *f->mutable_energy() = energy;
  f->set_energy_time_ticks(energy_time_ticks);
}

wire::EnergyTerms energy_terms(const PaperPort& port) {
  const auto& x = port.solver->energy();
  wire::EnergyTerms e;
  e.set_kinetic_j(x.kinetic_J);
  e.set_internal_j(x.internal_J);
  e.set_hourglass_j(x.hourglass_J);
  e.set_contact_j(x.contact_J);
  e.set_external_work_j(x.external_work_J);
  e.set_coupling_work_j(x.coupling_work_J);
  e.set_coupled_kinetic_j(cosim::product_kinetic_energy(*port.solver, port.reference));
  return e;
}

void apply_correction(PaperPort& port, const wire::Correction& c, const std::string& domain) {
  const std::size_t n3 = 3 * port.nodes.size();
  if (static_cast<std::size_t>(c.accelerations_m_s2_size()) != n3)
    throw ProtocolError(
        "coordinator",
        fmt::format("a Correction for domain '{}' at tick {} has {} accelerations "
                    "for its {} coupled nodes ({} expected)",
                    domain, c.time_ticks(), c.accelerations_m_s2_size(), port.nodes.size(), n3));
  auto& s = *port.solver;
  const auto& fixed = s.model().fixed;
  for (std::size_t j = 0; j < port.nodes.size(); ++j) {
    const auto l = port.nodes[j].local;
    Vec3 a{};
    for (std::size_t d = 0; d < 3; ++d) {
      const double x = c.accelerations_m_s2(static_cast<int>(3 * j + d));
      if (!std::isfinite(x))
        throw ProtocolError("coordinator",
                            fmt::format("a Correction for domain '{}' at tick {} gives node id {} "
                                        "the acceleration {}",
                                        domain, c.time_ticks(), s.model().nodes.id[l], x));
      const bool held = !fixed.empty() && (fixed[l] & (1u << d));
      a[d] = held ? 0.0 : x;
    }
    s.set_acceleration(l, a);
  }
}

}  // namespace crashlink::daemon
