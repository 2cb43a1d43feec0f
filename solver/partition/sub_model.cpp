// Building one domain's sub-model from a placement (partition_detail.h). Ids are the global ones,
// indices local; nodes are numbered in ascending global order.
#include <algorithm>

#include "core/errors.h"
#include "solver/contact/segments.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition::detail {

namespace {

using Index = std::int32_t;

bool kinematic_here(std::uint8_t role) {
  return role == kOwned || role == kCopy;
}

}  // namespace

DomainModel build_domain(const Analysis& a, const Placement& pl, int d) {
  const model::Model& g = *a.global;
  const auto du = static_cast<std::size_t>(d);
  const auto& role = pl.role[du];
  DomainModel out;
  out.name = a.domain_name[du];
  model::Model& m = out.model;
  m.name = out.name;
  m.materials = g.materials;  // all of them: simpler, and material indices stay global
  m.controls = g.controls;
  m.controls.model_energy_scale_J = a.energy_scale_J;  // the guard judges at the model's scale

  // Nodes.
  const std::size_t n = a.node_count();
  std::vector<Index> g2l(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (role[i] == kAbsent) continue;
    g2l[i] = static_cast<Index>(out.global_node.size());
    out.global_node.push_back(static_cast<Index>(i));
    m.nodes.id.push_back(g.nodes.id[i]);
    for (std::size_t k = 0; k < 3; ++k) m.nodes.x0.push_back(g.nodes.x0[3 * i + k]);
    out.ghost.push_back(role[i] == kGhost ? 1 : 0);
    out.copy.push_back(role[i] == kCopy ? 1 : 0);
    out.interface_mass_kg.push_back(pl.summed[i] && kinematic_here(role[i]) ? a.mass_kg[i] : 0.0);
  }
  auto local = [&](Index global_node) {
    const Index l = g2l[static_cast<std::size_t>(global_node)];
    if (l < 0)
      throw ModelError(
          fmt::format("domain '{}': node {} is used here but was not placed (internal "
                      "error of the decomposition)",
                      out.name, g.nodes.id[static_cast<std::size_t>(global_node)]));
    return l;
  };

  // Parts: the global parts restricted to the elements placed here, in global part order.
  std::vector<int> g2l_part(g.parts.size(), -1);
  for (std::size_t p = 0; p < g.parts.size(); ++p) {
    const auto& gp = g.parts[p];
    std::vector<Index> elems;
    for (std::size_t e = a.offset[p]; e < a.offset[p + 1]; ++e)
      if (pl.elem_domain[e] == d) elems.push_back(a.elem_local[e]);
    if (elems.empty()) continue;
    // The elements on a ghost node (the moved layer's outer row, next to J) last, each group in
    // global order: the solver computes the others while it waits for the ghosts' motion
    // (Solver::interior_elements, docs/design.md §2.6 "Overlap").
    const auto k = static_cast<std::size_t>(model::nodes_per_element(gp.kind));
    std::stable_partition(elems.begin(), elems.end(), [&](Index le) {
      const auto* c = gp.connectivity.data() + k * static_cast<std::size_t>(le);
      return std::none_of(c, c + k,
                          [&](Index gi) { return role[static_cast<std::size_t>(gi)] == kGhost; });
    });
    model::Part lp;
    lp.name = gp.name;
    lp.kind = gp.kind;
    lp.material = gp.material;
    lp.thickness_m = gp.thickness_m;
    lp.through_thickness_points = gp.through_thickness_points;
    lp.hourglass_coefficient = gp.hourglass_coefficient;
    lp.user_id = gp.user_id;
    lp.damping_ratio = gp.damping_ratio;
    // Interface damping (Placement::elem_damping_ratio): max(own, interface) per element; the
    // per-element vector is only created when some element of the part gets more than its own.
    bool raised = false;
    std::vector<double> xi_here;
    if (!pl.elem_damping_ratio.empty()) {
      for (Index le : elems) {
        const auto ue = static_cast<std::size_t>(le);
        const double own = gp.damping_ratio_of(ue);
        const double xi = std::max(own, pl.elem_damping_ratio[a.offset[p] + ue]);
        raised = raised || xi != own;
        xi_here.push_back(xi);
      }
    }
    if (raised) lp.element_damping_ratio = std::move(xi_here);
    for (Index le : elems) {
      const auto ue = static_cast<std::size_t>(le);
      for (std::size_t j = 0; j < k; ++j)
        lp.connectivity.push_back(local(gp.connectivity[k * ue + j]));
      lp.element_id.push_back(gp.element_id[ue]);
      // per-element damping ratios sliced with the element subset
      if (!gp.element_damping_ratio.empty() && !raised)
        lp.element_damping_ratio.push_back(gp.element_damping_ratio[ue]);
      if (!gp.element_thickness_m.empty())
        lp.element_thickness_m.push_back(gp.element_thickness_m[ue]);
      if (!gp.element_density_scale.empty())
        lp.element_density_scale.push_back(gp.element_density_scale[ue]);
    }
    g2l_part[p] = static_cast<int>(m.parts.size());
    m.parts.push_back(std::move(lp));
    out.part_global.push_back(static_cast<int>(p));
    out.part_elements.push_back(std::move(elems));
  }
  auto whole_part = [&](int gp) {
    const int lp = g2l_part[static_cast<std::size_t>(gp)];
    return lp >= 0 && m.parts[static_cast<std::size_t>(lp)].element_count() ==
                          g.parts[static_cast<std::size_t>(gp)].element_count();
  };

  // Boundary conditions: kinematic ones on every non-ghost presence (owned nodes and copies:
  // a copy must start and stay with its original), loads on the primary presence only (a force
  // counted once).
  if (!g.fixed.empty()) {
    m.fixed.assign(out.global_node.size(), 0);
    for (std::size_t l = 0; l < out.global_node.size(); ++l) {
      const auto gi = static_cast<std::size_t>(out.global_node[l]);
      if (kinematic_here(role[gi])) m.fixed[l] = g.fixed[gi];
    }
  }
  auto restrict_nodes = [&](const std::vector<Index>& nodes, bool primary_only) {
    std::vector<Index> r;
    for (Index gi : nodes) {
      const auto u = static_cast<std::size_t>(gi);
      if (primary_only ? (pl.primary[u] == d && role[u] == kOwned) : kinematic_here(role[u]))
        r.push_back(g2l[u]);
    }
    return r;
  };
  for (const auto& pv : g.prescribed_velocities) {
    if (pv.rigid_body >= 0) continue;  // with the bodies, below
    auto nodes = restrict_nodes(pv.nodes, false);
    if (nodes.empty()) continue;
    m.prescribed_velocities.push_back({pv.name, std::move(nodes), pv.dof, pv.velocity});
  }
  for (const auto& w : g.rigid_walls) {  // a kinematic condition, as a prescribed velocity
    auto nodes = restrict_nodes(w.nodes, false);
    if (nodes.empty()) continue;
    // A moving wall's motion follows from every node it meets: all of them in one domain.
    if (w.moving() && nodes.size() != w.nodes.size())
      throw ModelError(fmt::format(
          "moving rigid wall '{}': {} of its {} nodes are in domain '{}', the others elsewhere; a "
          "moving wall is computed in one domain (fix: put the parts it meets in one domain, or "
          "give it only the nodes of one domain's parts)",
          w.name, nodes.size(), w.nodes.size(), out.name));
    model::RigidWall sw = w;
    sw.nodes = std::move(nodes);
    m.rigid_walls.push_back(std::move(sw));
  }
  for (const auto& ld : g.loads) {
    auto nodes = restrict_nodes(ld.nodes, true);
    if (nodes.empty()) continue;
    m.loads.push_back({ld.name, std::move(nodes), ld.dof, ld.force});
  }
  for (const auto& iv : g.initial_velocities) {
    // Ghosts too: their motion is prescribed from t = 0 on, but the forces at t = 0 (bulk
    // viscosity, rates) need their initial velocity; their kinetic energy is not counted here.
    std::vector<Index> nodes;
    for (Index gi : iv.nodes) {
      const auto u = static_cast<std::size_t>(gi);
      if (kinematic_here(role[u]) || role[u] == kGhost) nodes.push_back(g2l[u]);
    }
    if (nodes.empty()) continue;
    model::InitialVelocity liv = iv;
    liv.nodes = std::move(nodes);
    m.initial_velocities.push_back(std::move(liv));
  }

  // Rigid bodies: whole, or not at all (one set of dofs): its parts and its extra nodes, which
  // this domain integrates (owned) or none of them.
  std::vector<int> g2l_body(g.rigid_bodies.size(), -1);
  for (std::size_t b = 0; b < g.rigid_bodies.size(); ++b) {
    const auto& rb = g.rigid_bodies[b];
    std::size_t here = 0, nodes_here = 0;
    for (int p : rb.parts) here += whole_part(p) ? 1 : 0;
    for (auto i : rb.nodes) nodes_here += role[static_cast<std::size_t>(i)] == kOwned ? 1 : 0;
    if (here == 0 && nodes_here == 0) continue;
    if (here != rb.parts.size() || nodes_here != rb.nodes.size())
      throw ModelError(
          fmt::format("domain '{}' holds only part of rigid body '{}' ({} of {} parts, {} of {} "
                      "extra nodes; internal error of the decomposition)",
                      out.name, rb.name, here, rb.parts.size(), nodes_here, rb.nodes.size()));
    model::RigidBody lb = rb;
    for (int& p : lb.parts) p = g2l_part[static_cast<std::size_t>(p)];
    for (auto& i : lb.nodes) i = local(i);
    g2l_body[b] = static_cast<int>(m.rigid_bodies.size());
    m.rigid_bodies.push_back(std::move(lb));
  }
  for (const auto& pv : g.prescribed_velocities)  // a body's motion where the body is
    if (pv.rigid_body >= 0 && g2l_body[static_cast<std::size_t>(pv.rigid_body)] >= 0) {
      model::PrescribedVelocity lp = pv;
      lp.rigid_body = g2l_body[static_cast<std::size_t>(pv.rigid_body)];
      m.prescribed_velocities.push_back(std::move(lp));
    }

  // Contacts placed here, remapped to local slave nodes and master parts.
  for (std::size_t c = 0; c < g.contacts.size(); ++c) {
    if (g.contacts[c].kind == model::ContactKind::SingleSurface) {
      // Over this domain's elements of its parts (moved layers included): folds within a domain
      // are found, a fold across a cut between two domains is not (docs/scenario-format.md).
      model::Contact lc = g.contacts[c];
      lc.master_parts.clear();
      for (int p : g.contacts[c].master_parts)
        if (g2l_part[static_cast<std::size_t>(p)] >= 0)
          lc.master_parts.push_back(g2l_part[static_cast<std::size_t>(p)]);
      if (!lc.master_parts.empty()) m.contacts.push_back(std::move(lc));
      continue;
    }
    if (pl.contact_domain[c] != d) continue;
    model::Contact lc = g.contacts[c];
    // Two-pass: the slave faces are taken on the whole model, where a face between two
    // hexahedra of different domains is not surface (in the sub-model it looks exterior).
    // The `paper` scheme's contact domain holds copies of the other domain's slave nodes, not
    // their elements: one pass there (docs/paper-scheme.md).
    const bool copies = std::any_of(lc.slave_nodes.begin(), lc.slave_nodes.end(), [&](Index i) {
      return role[static_cast<std::size_t>(i)] == kCopy;
    });
    if (lc.kind == model::ContactKind::SurfaceToSurface && copies) {
      lc.kind = model::ContactKind::NodeToSurface;
      lc.slave_faces.clear();
    }
    if (lc.kind == model::ContactKind::SurfaceToSurface && lc.slave_faces.empty())
      lc.slave_faces = contact::slave_faces(g, lc.slave_nodes, lc.master_parts);
    for (auto& s : lc.slave_nodes) s = local(s);
    for (auto& s : lc.slave_faces) s = local(s);
    for (int& p : lc.master_parts) {
      if (!whole_part(p))
        throw ModelError(
            fmt::format("contact '{}': domain '{}' does not hold all of master part "
                        "'{}' (internal error of the decomposition)",
                        lc.name, out.name, g.parts[static_cast<std::size_t>(p)].name));
      p = g2l_part[static_cast<std::size_t>(p)];
    }
    m.contacts.push_back(std::move(lc));
  }

  // Probes: a node probe goes to the node's primary domain, a rigid-body probe with its body.
  for (const auto& pr : g.probes) {
    const auto i = static_cast<std::size_t>(pr.index);
    if (pr.kind == model::Probe::Kind::Node) {
      if (pl.primary[i] == d && role[i] == kOwned) m.probes.push_back({pr.name, pr.kind, g2l[i]});
    } else if (g2l_body[i] >= 0) {
      m.probes.push_back({pr.name, pr.kind, g2l_body[i]});
    }
  }

  try {
    model::validate(m);
  } catch (const ModelError& e) {
    throw ModelError(
        fmt::format("domain '{}': the sub-model does not validate: {}", out.name, e.what()));
  }
  return out;
}

void build_domains(const Analysis& a, const Placement& p, std::size_t domain_count,
                   Decomposition& out) {
  for (std::size_t d = 0; d < domain_count; ++d) {
    out.domains.push_back(build_domain(a, p, static_cast<int>(d)));
    out.domain_dt_s.push_back(initial_step_s(out.domains.back().model));
  }
}

}  // namespace crashlink::partition::detail
