// The `paper` decomposition (docs/design.md §2.2, §2.5; §2.3 and §3.1 of Bourel 2005).
//
// No element moves. A node used by elements of several domains (the link interface Gamma of
// [3]-[4]) is present in each of them with its partial lumped mass m^k; interface_mass_kg gives
// the sum M = sum_k m^k of §2.2 for convenience (the coordinator sums the free accelerations,
// [8]). The reference side for the drift correction [11] of a link is the larger-step domain.
// A contact whose master parts lie in domain A and whose slave nodes lie in B is computed in A on
// COPIES of B's slave nodes (§3.1: "copier une partie des noeuds du sous-domaine esclave B dans le
// sous-domaine A"): no element, no own mass, tied to the original by the link [8]; the original's
// domain is the reference.
#include <algorithm>
#include <map>
#include <set>

#include "core/errors.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition::detail {

Decomposition decompose_paper(const Analysis& a) {
  const model::Model& g = *a.global;
  const std::size_t n = a.node_count(), nd = a.domain_count();
  Placement pl;
  pl.elem_domain = a.orig_domain;
  pl.role.assign(nd, std::vector<std::uint8_t>(n, kAbsent));
  pl.primary.assign(n, -1);
  pl.summed.assign(n, 0);
  std::map<std::pair<int, int>, std::vector<std::int32_t>> shared;  // (fine, coarse) -> nodes
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<int> used;
    for (std::size_t k = a.node_start[i]; k < a.node_start[i + 1]; ++k) {
      const int d = a.orig_domain[static_cast<std::size_t>(a.node_elems[k])];
      if (std::find(used.begin(), used.end(), d) == used.end()) used.push_back(d);
    }
    if (used.empty()) used.push_back(0);  // a node of no element: the first domain keeps it
    std::sort(used.begin(), used.end());
    int ref = used.front();
    for (int d : used) {
      pl.role[static_cast<std::size_t>(d)][i] = kOwned;
      if (a.finer(ref, d)) ref = d;  // the larger step
    }
    pl.primary[i] = ref;
    if (used.size() == 1) continue;
    pl.summed[i] = 1;
    for (std::size_t x = 0; x < used.size(); ++x)
      for (std::size_t y = x + 1; y < used.size(); ++y) {
        const int f = a.finer(used[x], used[y]) ? used[x] : used[y];
        const int c = f == used[x] ? used[y] : used[x];
        shared[{f, c}].push_back(static_cast<std::int32_t>(i));
      }
  }

  Decomposition out;
  out.scheme = Scheme::Paper;
  for (const auto& [pr, nodes] : shared) {
    Interface itf;
    itf.fine = pr.first;
    itf.coarse = pr.second;
    itf.reference = pr.second;
    itf.j_nodes_global = nodes;
    for (auto j : nodes) itf.j_mass_kg.push_back(a.mass_kg[static_cast<std::size_t>(j)]);
    itf.kind = "link";
    out.interfaces.push_back(std::move(itf));
  }

  // Contacts: in the master's domain A; slave nodes A does not have become copies in A.
  pl.contact_domain.assign(g.contacts.size(), -1);
  for (std::size_t c = 0; c < g.contacts.size(); ++c) {
    if (g.contacts[c].kind == model::ContactKind::SingleSurface)
      throw ModelError(fmt::format(
          "contact '{}': a single_surface contact is not supported by the `paper` scheme; use "
          "`layer` (the default), where each domain computes it over its own elements",
          g.contacts[c].name));
    const ContactSides s = contact_sides(a, c);
    const int A = s.master_domain;
    pl.contact_domain[c] = A;
    std::map<int, std::vector<std::int32_t>> copies;  // reference domain -> copied nodes
    for (auto node : g.contacts[c].slave_nodes) {
      const auto i = static_cast<std::size_t>(node);
      auto& r = pl.role[static_cast<std::size_t>(A)][i];
      if (r == kOwned) continue;
      r = kCopy;
      pl.summed[i] = 1;  // the copy adds no mass: M is the original's natural mass
      copies[pl.primary[i]].push_back(node);
    }
    for (auto& [ref, nodes] : copies) {
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      Interface itf;
      itf.fine = a.finer(A, ref) ? A : ref;
      itf.coarse = a.finer(A, ref) ? ref : A;
      itf.reference = ref;
      itf.j_nodes_global = nodes;
      for (auto j : nodes) itf.j_mass_kg.push_back(a.mass_kg[static_cast<std::size_t>(j)]);
      itf.kind = "contact:" + g.contacts[c].name;
      out.interfaces.push_back(std::move(itf));
    }
  }
  build_domains(a, pl, nd, out);
  return out;
}

}  // namespace crashlink::partition::detail
