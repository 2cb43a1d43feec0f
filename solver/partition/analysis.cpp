// The analysis of the global model shared by both schemes (partition_detail.h).
#include <fmt/ranges.h>

#include <algorithm>
#include <limits>

#include "core/errors.h"
#include "solver/integration/energy_scale.h"
#include "solver/integration/solver.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition::detail {

namespace {

void check_domains(const model::Model& g, std::vector<int>& part_domain) {
  part_domain.assign(g.parts.size(), -1);
  for (std::size_t d = 0; d < g.domains.size(); ++d) {
    const auto& dom = g.domains[d];
    if (dom.parts.empty())
      throw ModelError(fmt::format(
          "domain '{}' holds no part; give it at least one part or remove it", dom.name));
    for (std::size_t e = 0; e < d; ++e)
      if (g.domains[e].name == dom.name)
        throw ModelError(
            fmt::format("domain name '{}' is used twice; give each domain its own name", dom.name));
    for (int p : dom.parts) {
      if (p < 0 || static_cast<std::size_t>(p) >= g.parts.size())
        throw ModelError(fmt::format("domain '{}': part index {} out of range (have {} parts)",
                                     dom.name, p, g.parts.size()));
      auto& owner = part_domain[static_cast<std::size_t>(p)];
      if (owner >= 0)
        throw ModelError(fmt::format(
            "part '{}' is in domains '{}' and '{}'; a part belongs to exactly one domain",
            g.parts[static_cast<std::size_t>(p)].name,
            g.domains[static_cast<std::size_t>(owner)].name, dom.name));
      owner = static_cast<int>(d);
    }
  }
  std::vector<std::string> orphans;
  for (std::size_t p = 0; p < g.parts.size(); ++p)
    if (part_domain[p] < 0) orphans.push_back("'" + g.parts[p].name + "'");
  if (!orphans.empty())
    throw ModelError(fmt::format("parts {} are in no domain; add each to exactly one domain",
                                 fmt::join(orphans, ", ")));
  for (const auto& rb : g.rigid_bodies)
    for (int p : rb.parts)
      if (part_domain[static_cast<std::size_t>(p)] !=
          part_domain[static_cast<std::size_t>(rb.parts.front())])
        throw ModelError(fmt::format(
            "rigid body '{}' has parts in domains '{}' and '{}'; a rigid body is one set of dofs: "
            "put all its parts in one domain",
            rb.name,
            g.domains[static_cast<std::size_t>(
                          part_domain[static_cast<std::size_t>(rb.parts.front())])]
                .name,
            g.domains[static_cast<std::size_t>(part_domain[static_cast<std::size_t>(p)])].name));
}

}  // namespace

std::int64_t Analysis::element_id(std::size_t e) const {
  return global->parts[static_cast<std::size_t>(elem_part[e])]
      .element_id[static_cast<std::size_t>(elem_local[e])];
}

const std::int32_t* Analysis::element_nodes(std::size_t e, int& k) const {
  const auto& p = global->parts[static_cast<std::size_t>(elem_part[e])];
  k = model::nodes_per_element(p.kind);
  return p.connectivity.data() +
         static_cast<std::size_t>(k) * static_cast<std::size_t>(elem_local[e]);
}

Analysis analyse(const model::Model& g) {
  Analysis a;
  a.global = &g;
  if (g.domains.empty()) {
    a.domain_name = {"model"};
    a.part_domain.assign(g.parts.size(), 0);
  } else {
    check_domains(g, a.part_domain);
    for (const auto& d : g.domains) a.domain_name.push_back(d.name);
  }
  // Elements, flat numbering.
  a.offset.assign(g.parts.size() + 1, 0);
  for (std::size_t p = 0; p < g.parts.size(); ++p)
    a.offset[p + 1] = a.offset[p] + g.parts[p].element_count();
  const std::size_t ne = a.offset.back();
  a.elem_part.resize(ne);
  a.elem_local.resize(ne);
  a.orig_domain.resize(ne);
  for (std::size_t p = 0; p < g.parts.size(); ++p)
    for (std::size_t k = 0; k < g.parts[p].element_count(); ++k) {
      a.elem_part[a.offset[p] + k] = static_cast<int>(p);
      a.elem_local[a.offset[p] + k] = static_cast<std::int32_t>(k);
      a.orig_domain[a.offset[p] + k] = a.part_domain[p];
    }
  // Node -> elements (CSR; an element listed once per node even for a degenerate triangle).
  const std::size_t n = g.nodes.count();
  std::vector<std::vector<std::int32_t>> lists(n);
  for (std::size_t e = 0; e < ne; ++e) {
    int k = 0;
    const std::int32_t* c = a.element_nodes(e, k);
    for (int j = 0; j < k; ++j) {
      auto& l = lists[static_cast<std::size_t>(c[j])];
      if (l.empty() || l.back() != static_cast<std::int32_t>(e))
        l.push_back(static_cast<std::int32_t>(e));
    }
  }
  a.node_start.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) a.node_start[i + 1] = a.node_start[i] + lists[i].size();
  a.node_elems.reserve(a.node_start.back());
  for (const auto& l : lists) a.node_elems.insert(a.node_elems.end(), l.begin(), l.end());
  // Rigid bodies.
  a.body_of_part.assign(g.parts.size(), -1);
  for (std::size_t b = 0; b < g.rigid_bodies.size(); ++b)
    for (int p : g.rigid_bodies[b].parts)
      a.body_of_part[static_cast<std::size_t>(p)] = static_cast<int>(b);
  // A body's extra nodes (a nodal rigid body) and the elements around them: in one domain, the
  // body's (one set of dofs; the elements are not moved for it).
  for (const auto& rb : g.rigid_bodies) {
    int dom = rb.parts.empty() ? -1 : a.part_domain[static_cast<std::size_t>(rb.parts.front())];
    for (auto i : rb.nodes)
      for (std::size_t k = a.node_start[static_cast<std::size_t>(i)];
           k < a.node_start[static_cast<std::size_t>(i) + 1]; ++k) {
        const int d = a.orig_domain[static_cast<std::size_t>(a.node_elems[k])];
        if (dom < 0) dom = d;
        if (d != dom)
          throw ModelError(fmt::format(
              "rigid body '{}' holds node {}, which elements of domains '{}' and '{}' use; a "
              "rigid body is one set of dofs: put the parts around its nodes in one domain",
              rb.name, g.nodes.id[static_cast<std::size_t>(i)],
              a.domain_name[static_cast<std::size_t>(dom)],
              a.domain_name[static_cast<std::size_t>(d)]));
      }
  }
  // Per-part stable steps and natural lumped masses from the single-domain solver (the stable
  // step comes from one function, docs/design.md §7 rule 10).
  integration::Solver solver(g, "global");
  solver.initialize();
  a.mass_kg = solver.mass();
  a.energy_scale_J =
      std::max(g.controls.model_energy_scale_J, integration::model_energy_scale_J(solver));
  const double inf = std::numeric_limits<double>::infinity();
  a.part_dt_s.assign(g.parts.size(), inf);
  for (std::size_t p = 0; p < g.parts.size(); ++p)
    if (!is_rigid(g, g.parts[p]))
      a.part_dt_s[p] = g.controls.dt_scale * solver.parts()[p].last.dt_stable_s;
  a.orig_dt_s.assign(a.domain_count(), inf);
  for (std::size_t p = 0; p < g.parts.size(); ++p) {
    auto& dt = a.orig_dt_s[static_cast<std::size_t>(a.part_domain[p])];
    dt = std::min(dt, a.part_dt_s[p]);
  }
  return a;
}

ContactSides contact_sides(const Analysis& a, std::size_t ci) {
  const model::Model& g = *a.global;
  const auto& c = g.contacts[ci];
  ContactSides s;
  // A single-surface contact is computed in every domain holding its parts' elements, each over
  // its own (sub_model.cpp): no side, no surface to gather, nothing moves for it.
  if (c.kind == model::ContactKind::SingleSurface) return s;
  for (int p : c.master_parts) {
    const int d = a.part_domain[static_cast<std::size_t>(p)];
    if (s.master_domain >= 0 && d != s.master_domain)
      throw ModelError(fmt::format(
          "contact '{}': its master parts lie in domains '{}' and '{}'; split it into one contact "
          "per domain of the master surface",
          c.name, a.domain_name[static_cast<std::size_t>(s.master_domain)],
          a.domain_name[static_cast<std::size_t>(d)]));
    s.master_domain = d;
  }
  // Greedy cover of the slave nodes by domains, the master's first.
  const std::size_t ns = c.slave_nodes.size();
  s.slave_home.assign(ns, -1);
  auto uses = [&](std::size_t node, int d) {
    for (std::size_t k = a.node_start[node]; k < a.node_start[node + 1]; ++k)
      if (a.orig_domain[static_cast<std::size_t>(a.node_elems[k])] == d) return true;
    return false;
  };
  std::size_t left = ns;
  int d = s.master_domain;
  while (left > 0) {
    for (std::size_t j = 0; j < ns; ++j)
      if (s.slave_home[j] < 0 && uses(static_cast<std::size_t>(c.slave_nodes[j]), d)) {
        s.slave_home[j] = d;
        --left;
      }
    if (d != s.master_domain) s.slave_domains.push_back(d);
    if (left == 0) break;
    std::vector<std::size_t> count(a.domain_count(), 0);
    for (std::size_t j = 0; j < ns; ++j) {
      if (s.slave_home[j] >= 0) continue;
      const auto node = static_cast<std::size_t>(c.slave_nodes[j]);
      if (a.node_start[node] == a.node_start[node + 1])
        throw ModelError(
            fmt::format("contact '{}': slave node {} belongs to no element; remove it "
                        "from the slave set",
                        c.name, a.node_id(node)));
      std::vector<std::uint8_t> seen(a.domain_count(), 0);
      for (std::size_t k = a.node_start[node]; k < a.node_start[node + 1]; ++k)
        seen[static_cast<std::size_t>(a.orig_domain[static_cast<std::size_t>(a.node_elems[k])])] =
            1;
      for (std::size_t q = 0; q < seen.size(); ++q) count[q] += seen[q];
    }
    d = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
  }
  std::sort(s.slave_domains.begin(), s.slave_domains.end());
  if (s.slave_domains.size() > 1)
    throw ModelError(fmt::format(
        "contact '{}': its slave nodes lie in domains {} besides the master's domain '{}'; a "
        "contact couples at most two domains: split it into one contact per slave domain",
        c.name,
        fmt::join(
            std::vector<std::string>{a.domain_name[static_cast<std::size_t>(s.slave_domains[0])],
                                     a.domain_name[static_cast<std::size_t>(s.slave_domains[1])]},
            ", "),
        a.domain_name[static_cast<std::size_t>(s.master_domain)]));
  // Surface elements: the master parts' elements and the covering domains' elements that hold a
  // slave node.
  std::vector<std::uint8_t> mark(a.element_count(), 0);
  for (int p : c.master_parts)
    for (std::size_t e = a.offset[static_cast<std::size_t>(p)];
         e < a.offset[static_cast<std::size_t>(p) + 1]; ++e)
      mark[e] = 1;
  for (std::size_t j = 0; j < ns; ++j) {
    const auto node = static_cast<std::size_t>(c.slave_nodes[j]);
    for (std::size_t k = a.node_start[node]; k < a.node_start[node + 1]; ++k) {
      const auto e = static_cast<std::size_t>(a.node_elems[k]);
      if (a.orig_domain[e] == s.master_domain ||
          (!s.slave_domains.empty() && a.orig_domain[e] == s.slave_domains[0]))
        mark[e] = 1;
    }
  }
  for (std::size_t e = 0; e < mark.size(); ++e)
    if (mark[e]) s.surface.push_back(static_cast<std::int32_t>(e));
  return s;
}

double initial_step_s(const model::Model& m) {
  // The deformable parts alone: rigid bodies, contacts and conditions do not bound the element
  // step (contact springs are sized at the fine step, docs/design.md §2.7).
  model::Model probe;
  probe.name = m.name;
  probe.nodes = m.nodes;
  probe.materials = m.materials;
  probe.controls = m.controls;
  probe.controls.dt_max_s = 0.0;
  for (const auto& p : m.parts)
    if (!is_rigid(m, p)) probe.parts.push_back(p);
  if (probe.parts.empty()) return std::numeric_limits<double>::infinity();
  integration::Solver solver(probe, m.name);
  solver.initialize();
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& r : solver.parts()) dt = std::min(dt, r.last.dt_stable_s);
  return m.controls.dt_scale * dt;
}

}  // namespace crashlink::partition::detail
