// The `layer` decomposition (docs/design.md §2.7, "How to distribute layer";
// docs/decomposition.md): steps 1-4 in decompose_layer, step 5 in interface_damping.
#include <algorithm>
#include <map>
#include <set>

#include "core/errors.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition::detail {

// Step 5 (partition_detail.h), interface damping (model::InterfaceDamping, off by default):
// stiffness-proportional damping on the elements within n element layers of J on both sides (the
// moved layer is the fine side's first), the coupling study's stabiliser of the layer scheme in
// 2-D/3-D. The element layers around J, breadth-first from the seed nodes.
std::vector<double> interface_damping(const Analysis& a, const std::vector<std::uint8_t>& seed) {
  const model::Model& g = *a.global;
  const auto& idamp = g.coupling.interface_damping;
  if (!(idamp.ratio > 0.0)) return {};
  const std::size_t n = a.node_count(), ne = a.element_count();
  std::vector<std::uint8_t> node_in(seed), elem_in(ne, 0);
  std::vector<std::int32_t> front;
  for (std::size_t i = 0; i < n; ++i)
    if (seed[i]) front.push_back(static_cast<std::int32_t>(i));
  // Breadth-first over the element-node adjacency, one element layer per pass.
  for (int layer = 0; layer < idamp.layers && !front.empty(); ++layer) {
    std::vector<std::int32_t> next;
    for (std::int32_t i : front)
      for (std::size_t k = a.node_start[static_cast<std::size_t>(i)];
           k < a.node_start[static_cast<std::size_t>(i) + 1]; ++k) {
        const auto e = static_cast<std::size_t>(a.node_elems[k]);
        if (elem_in[e]) continue;
        elem_in[e] = 1;
        int kn = 0;
        const std::int32_t* en = a.element_nodes(e, kn);
        for (int j = 0; j < kn; ++j) {
          const auto u = static_cast<std::size_t>(en[j]);
          if (node_in[u]) continue;
          node_in[u] = 1;
          next.push_back(en[j]);
        }
      }
    front.swap(next);
  }
  std::vector<double> xi(ne, 0.0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto p = static_cast<std::size_t>(a.elem_part[e]);
    const bool rigid = g.materials[static_cast<std::size_t>(g.parts[p].material)].kind ==
                       materials::MaterialKind::Rigid;
    if (elem_in[e] && !rigid) xi[e] = idamp.ratio;  // a rigid part has no damping
  }
  return xi;
}

// 1. Link claims: every node used by elements of several domains is a permanent-link node; every
//    element touching it is claimed by the finest of those domains (the coarse side's first
//    element layer moves into F). Claims use the ORIGINAL assignment only: one layer, no cascade.
//    After 2.-3., `overlap_layers` times, the same claim on the assignment so far (the `lts`
//    overlap: F integrates that many more coarse element layers at its step, beyond the links'
//    and the contact surfaces' moved layers; docs/multirate.md "lts"), then 2.-3. again.
// 2. Contact claims: all surface elements of a contact (master parts' elements, the elements
//    holding slave nodes) go to the finest domain holding one of them, so the contact lies in one
//    domain (for a cross-domain contact: the coarse body's contact-surface layer moves into F).
// 3. Rigid bodies move whole (a rigid body is one set of dofs: it cannot be integrated by two
//    daemons). 2 and 3 are repeated to a fixed point; claims only ever go finer, so it ends.
// 4. Nodes: a node used by one domain is owned by it. A node used by several domains is owned by
//    the coarsest of them (the far nodes J of a moved layer: integrated at the coarse step with
//    their natural summed mass, the link sum [8]) and is a read-only ghost in the others.
//    Check: no element of an originally finer domain touches a node owned by a coarser one (it
//    would be integrated above its stable step).
// 5. Interface damping: interface_damping above.
Decomposition decompose_layer(const Analysis& a, int overlap_layers) {
  const model::Model& g = *a.global;
  if (overlap_layers > 0 && g.coupling.interface_damping.ratio > 0.0)
    throw ModelError(fmt::format(
        "layer decomposition: coupling.interface_damping (ratio {}) with {} overlap layers (the "
        "lts coupling): it would damp the elements lts drives on its reflected ghost path, and "
        "lts conserves its energy without it; remove coupling.interface_damping, or run "
        "--coupling layer",
        g.coupling.interface_damping.ratio, overlap_layers));
  const std::size_t ne = a.element_count(), n = a.node_count(), nd = a.domain_count();
  auto finest = [&](int x, int y) { return a.finer(x, y) ? x : y; };

  Placement pl;
  pl.elem_domain = a.orig_domain;
  // Reasons an element moved: bit 0 link, contact c -> entry in contact_moved.
  std::vector<std::uint8_t> link_moved(ne, 0);

  // The link claim on `assigned`: every element touching a node used by several domains of
  // `assigned` goes into `into` as the finest of them (marked in `mark` when given).
  const auto claim_links = [&](const std::vector<int>& assigned, std::vector<int>& into,
                               std::uint8_t* mark) {
    for (std::size_t i = 0; i < n; ++i) {
      int f = -1;
      bool shared = false;
      for (std::size_t k = a.node_start[i]; k < a.node_start[i + 1]; ++k) {
        const int d = assigned[static_cast<std::size_t>(a.node_elems[k])];
        if (f >= 0 && d != f) shared = true;
        f = f < 0 ? d : finest(f, d);
      }
      if (!shared) continue;
      for (std::size_t k = a.node_start[i]; k < a.node_start[i + 1]; ++k) {
        const auto e = static_cast<std::size_t>(a.node_elems[k]);
        if (assigned[e] == f) continue;
        into[e] = finest(into[e], f);
        if (mark != nullptr) mark[e] = 1;
      }
    }
  };

  // 1. Link claims on the original assignment.
  claim_links(a.orig_domain, pl.elem_domain, link_moved.data());

  // 2.-3. Contact surfaces and rigid bodies, to a fixed point.
  std::vector<ContactSides> sides;
  for (std::size_t c = 0; c < g.contacts.size(); ++c) sides.push_back(contact_sides(a, c));
  std::vector<std::vector<std::int32_t>> body_elems(g.rigid_bodies.size());
  for (std::size_t b = 0; b < g.rigid_bodies.size(); ++b) {
    for (int p : g.rigid_bodies[b].parts)
      for (std::size_t e = a.offset[static_cast<std::size_t>(p)];
           e < a.offset[static_cast<std::size_t>(p) + 1]; ++e)
        body_elems[b].push_back(static_cast<std::int32_t>(e));
    // and the elements around its extra nodes: one domain integrates them all
    for (auto i : g.rigid_bodies[b].nodes)
      for (std::size_t k = a.node_start[static_cast<std::size_t>(i)];
           k < a.node_start[static_cast<std::size_t>(i) + 1]; ++k)
        body_elems[b].push_back(a.node_elems[k]);
  }
  auto gather = [&](const std::vector<std::int32_t>& elems) {
    int f = -1;
    for (auto e : elems) {
      const int d = pl.elem_domain[static_cast<std::size_t>(e)];
      f = f < 0 ? d : finest(f, d);
    }
    for (auto e : elems) pl.elem_domain[static_cast<std::size_t>(e)] = f;
    return f;
  };
  pl.contact_domain.assign(g.contacts.size(), -1);
  // To a fixed point; true when anything moved. The last pass changes nothing, so every
  // contact's surface is in contact_domain.
  const auto claim_surfaces_and_bodies = [&] {
    bool moved = false;
    for (bool changed = true; changed;) {
      const auto before = pl.elem_domain;
      for (std::size_t c = 0; c < sides.size(); ++c)
        pl.contact_domain[c] = gather(sides[c].surface);
      for (const auto& be : body_elems) (void)gather(be);
      changed = before != pl.elem_domain;
      moved = moved || changed;
    }
    return moved;
  };
  claim_surfaces_and_bodies();

  // 1b. The overlap: the link claim again on the assignment so far (the links' and the contact
  //     surfaces' moved layers alike), one element layer per pass, `overlap_layers` passes; then
  //     2.-3. again, so that a rigid body or a contact surface the overlap reached moves whole;
  //     and when that moved anything, the passes again, so that the new boundary has its layers
  //     too (older boundaries then get more, which costs steps, not stability). Claims only go
  //     finer, so it ends. Overlap moves are not link reasons (an interface's kind).
  while (overlap_layers > 0) {
    for (int layer = 0; layer < overlap_layers; ++layer) {
      const std::vector<int> assigned = pl.elem_domain;
      claim_links(assigned, pl.elem_domain, nullptr);
    }
    if (!claim_surfaces_and_bodies()) break;
  }

  // 4. Node roles.
  pl.role.assign(nd, std::vector<std::uint8_t>(n, kAbsent));
  pl.primary.assign(n, -1);
  pl.summed.assign(n, 0);
  std::map<std::pair<int, int>, std::vector<std::int32_t>> j_of_pair;  // (fine, coarse) -> J
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<int> used;
    for (std::size_t k = a.node_start[i]; k < a.node_start[i + 1]; ++k) {
      const int d = pl.elem_domain[static_cast<std::size_t>(a.node_elems[k])];
      if (std::find(used.begin(), used.end(), d) == used.end()) used.push_back(d);
    }
    if (used.empty()) {
      // A node of no element: the first domain owns it, so that every node has one owner.
      pl.role[0][i] = kOwned;
      pl.primary[i] = 0;
      continue;
    }
    int owner = used.front();
    for (int d : used)
      if (a.finer(owner, d)) owner = d;  // the coarsest
    pl.primary[i] = owner;
    pl.role[static_cast<std::size_t>(owner)][i] = kOwned;
    if (used.size() == 1) continue;
    pl.summed[i] = 1;
    for (std::size_t k = a.node_start[i]; k < a.node_start[i + 1]; ++k) {
      const auto e = static_cast<std::size_t>(a.node_elems[k]);
      if (a.finer(a.orig_domain[e], owner))
        throw ModelError(fmt::format(
            "layer decomposition: node {} would be integrated by domain '{}' at {:.3e} s although "
            "element {} of domain '{}' (step {:.3e} s) touches it; this happens when a contact "
            "surface or rigid body moved into a domain is also linked to a finer one: put part "
            "'{}' in the same domain as the parts it is linked to",
            a.node_id(i), a.domain_name[static_cast<std::size_t>(owner)],
            a.orig_dt_s[static_cast<std::size_t>(owner)], a.element_id(e),
            a.domain_name[static_cast<std::size_t>(a.orig_domain[e])],
            a.orig_dt_s[static_cast<std::size_t>(a.orig_domain[e])],
            g.parts[static_cast<std::size_t>(a.elem_part[e])].name));
      const int fd = pl.elem_domain[e];
      if (fd != owner && a.body_of_part[static_cast<std::size_t>(a.elem_part[e])] >= 0)
        throw ModelError(fmt::format(
            "layer decomposition: node {} of rigid body '{}' (domain '{}') is also used by domain "
            "'{}', which would integrate it; a rigid body is one set of dofs: put the parts "
            "sharing its nodes in the body's domain",
            a.node_id(i),
            g.rigid_bodies[static_cast<std::size_t>(
                               a.body_of_part[static_cast<std::size_t>(a.elem_part[e])])]
                .name,
            a.domain_name[static_cast<std::size_t>(fd)],
            a.domain_name[static_cast<std::size_t>(owner)]));
    }
    for (int d : used)
      if (d != owner) {
        pl.role[static_cast<std::size_t>(d)][i] = kGhost;
        j_of_pair[{d, owner}].push_back(static_cast<std::int32_t>(i));
      }
  }

  // Interfaces: one per (fine, coarse) pair with J nodes or moved elements.
  std::map<std::pair<int, int>, std::vector<std::int64_t>> moved;
  std::map<std::pair<int, int>, std::set<std::size_t>> contact_reason;
  std::map<std::pair<int, int>, bool> link_reason;
  for (std::size_t e = 0; e < ne; ++e) {
    const int o = a.orig_domain[e], f = pl.elem_domain[e];
    if (o == f) continue;
    moved[{f, o}].push_back(a.element_id(e));
    if (link_moved[e]) link_reason[{f, o}] = true;
  }
  for (std::size_t c = 0; c < sides.size(); ++c) {
    const int f = pl.contact_domain[c];
    for (auto e : sides[c].surface) {
      const int o = a.orig_domain[static_cast<std::size_t>(e)];
      if (o != f) contact_reason[{f, o}].insert(c);
    }
  }
  std::set<std::pair<int, int>> pairs;
  for (const auto& kv : j_of_pair) pairs.insert(kv.first);
  for (const auto& kv : moved) pairs.insert(kv.first);
  Decomposition out;
  out.scheme = Scheme::Layer;
  out.overlap_layers = overlap_layers;
  for (const auto& pr : pairs) {
    Interface itf;
    itf.fine = pr.first;
    itf.coarse = pr.second;
    itf.reference = pr.second;
    if (auto it = j_of_pair.find(pr); it != j_of_pair.end()) itf.j_nodes_global = it->second;
    for (auto j : itf.j_nodes_global)
      itf.j_mass_kg.push_back(a.mass_kg[static_cast<std::size_t>(j)]);
    if (auto it = moved.find(pr); it != moved.end()) itf.moved_elements = it->second;
    std::sort(itf.moved_elements.begin(), itf.moved_elements.end());
    std::vector<std::string> why;
    const bool has_contact = contact_reason.count(pr) > 0;
    if (link_reason.count(pr) || !has_contact) why.push_back("link");
    if (has_contact)
      for (auto c : contact_reason[pr]) why.push_back("contact:" + g.contacts[c].name);
    for (std::size_t k = 0; k < why.size(); ++k) itf.kind += (k ? "+" : "") + why[k];
    out.interfaces.push_back(std::move(itf));
  }
  // 5. Interface damping (model::InterfaceDamping): the element layers around J on both sides.
  pl.elem_damping_ratio = interface_damping(a, pl.summed);
  build_domains(a, pl, nd, out);
  return out;
}

}  // namespace crashlink::partition::detail
