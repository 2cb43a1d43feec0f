// The coupled nodes of one domain of a `paper` cut (paper_nodes.h).
#include "solver/cosim/paper_nodes.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"

namespace crashlink::cosim {

std::vector<PaperNodeOfDomain> paper_nodes(const partition::Decomposition& dec, int d) {
  const auto& dm = dec.domains.at(static_cast<std::size_t>(d));
  std::vector<std::int64_t> local_of(dm.global_node.empty() ? 0 : dm.global_node.back() + 1, -1);
  for (std::size_t l = 0; l < dm.global_node.size(); ++l)
    local_of[static_cast<std::size_t>(dm.global_node[l])] = static_cast<std::int64_t>(l);
  std::vector<PaperNodeOfDomain> out;
  std::vector<std::uint8_t> seen(local_of.size(), 0);
  for (std::size_t i = 0; i < dec.interfaces.size(); ++i) {
    const auto& itf = dec.interfaces[i];
    if (itf.fine != d && itf.coarse != d) continue;
    for (const auto gj : itf.j_nodes_global) {
      const auto g = static_cast<std::size_t>(gj);
      const std::int64_t l = g < local_of.size() ? local_of[g] : -1;
      if (l < 0)
        throw ModelError(fmt::format(
            "paper: coupled node {} of interface {} ({}) is missing from domain '{}' (internal "
            "error of the cut)",
            g, i, itf.kind, dm.name));
      if (seen[g])
        throw ModelError(fmt::format(
            "paper: a node of domain '{}' (global index {}) belongs to two interfaces (a link "
            "node that is also copied for a contact); the paper scheme couples each node once",
            dm.name, g));
      seen[g] = 1;
      PaperNodeOfDomain n;
      n.global = g;
      n.local = static_cast<std::size_t>(l);
      n.interface = static_cast<std::uint32_t>(i);
      n.partner = itf.fine == d ? itf.coarse : itf.fine;
      n.reference = itf.reference == d;
      n.copy = dm.copy[n.local] != 0;
      out.push_back(n);
    }
  }
  return out;
}

void refuse_rotations_on_both_sides(const partition::Decomposition& dec, int d,
                                    const std::vector<PaperNodeOfDomain>& nodes) {
  const auto& dm = dec.domains.at(static_cast<std::size_t>(d));
  std::vector<double> mass, inertia, partner_mass, partner_inertia;
  partial_masses(dm.model, mass, inertia);
  int loaded = -1;  // the partner whose inertia is in partner_inertia
  std::vector<std::int64_t> partner_local;
  for (const auto& n : nodes) {
    if (n.copy || !(inertia[n.local] > 0.0)) continue;
    const auto& pd = dec.domains[static_cast<std::size_t>(n.partner)];
    if (loaded != n.partner) {
      partial_masses(pd.model, partner_mass, partner_inertia);
      partner_local.assign(static_cast<std::size_t>(pd.global_node.back()) + 1, -1);
      for (std::size_t l = 0; l < pd.global_node.size(); ++l)
        partner_local[static_cast<std::size_t>(pd.global_node[l])] = static_cast<std::int64_t>(l);
      loaded = n.partner;
    }
    const auto pl = n.global < partner_local.size() ? partner_local[n.global] : -1;
    if (pl >= 0 && partner_inertia[static_cast<std::size_t>(pl)] > 0.0)
      throw ModelError(fmt::format(
          "paper: link node id {} carries rotations in domains '{}' and '{}' (a shell node shared "
          "by shells on both sides); the paper scheme couples translations only (the Solver has "
          "no hook to impose a corrected angular acceleration). Fix: use the `layer` scheme, or "
          "cut the model where no shell node is shared by shells of both domains",
          dm.model.nodes.id[n.local], dm.name, pd.name));
  }
}

void partial_masses(const model::Model& m, std::vector<double>& mass_kg,
                    std::vector<double>& inertia_kgm2) {
  mass_kg.assign(m.nodes.count(), 0.0);
  inertia_kgm2.assign(m.nodes.count(), 0.0);
  for (const auto& p : m.parts) {
    const auto& mat = m.materials[static_cast<std::size_t>(p.material)];
    if (p.kind == model::ElementKind::Hex8)
      elements::hex8_lumped_mass(p, mat, m.nodes.x0.data(), mass_kg.data());
    else
      elements::shell_lumped_mass(p, mat, m.nodes.x0.data(), mass_kg.data(), inertia_kgm2.data());
  }
}

double product_kinetic_energy(const integration::Solver& s, const std::vector<std::size_t>& nodes) {
  double e = 0.0;
  for (const std::size_t l : nodes) {
    const Vec3 vn = s.node_velocity(l);
    double p = 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      const double v = s.velocity_mid()[3 * l + d];
      p += (2.0 * vn[d] - v) * v;
    }
    e += 0.5 * s.mass()[l] * p;
  }
  return e;
}

}  // namespace crashlink::cosim
