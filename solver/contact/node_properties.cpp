#include "solver/contact/node_properties.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/contact/segments.h"

namespace crashlink::contact {

double reduced_mass(double a, double b) {
  if (std::isinf(a)) return b;
  if (std::isinf(b)) return a;
  return a + b > 0.0 ? a * b / (a + b) : 0.0;
}

NodeProperties node_properties(const model::Model& m, const model::Contact& c, const double* mass) {
  const double penalty_scale = c.penalty_scale;
  const std::size_t n = m.nodes.count();
  NodeProperties np;
  np.half_thickness_m.assign(n, 0.0);
  np.stiffness_N_m.assign(n, 0.0);
  np.mass_kg.assign(n, 0.0);
  const double* x0 = m.nodes.x0.data();
  // The contact's elements: those of its master parts and those holding a slave node. A cut
  // model holds all of them in the contact's domain (solver/partition), so what is taken from
  // them (offsets, stiffness, masses) is the same in mono and in that domain (a node shared with
  // a part of another domain counts only these).
  std::vector<std::uint8_t> slave(n, 0), master(m.parts.size(), 0);
  for (auto i : c.slave_nodes)
    if (i >= 0 && static_cast<std::size_t>(i) < n) slave[static_cast<std::size_t>(i)] = 1;
  for (int p : c.master_parts)
    if (p >= 0 && static_cast<std::size_t>(p) < m.parts.size())
      master[static_cast<std::size_t>(p)] = 1;
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const auto& part = m.parts[p];
    const auto& mat = m.materials[static_cast<std::size_t>(part.material)];
    const double K = mat.bulk_modulus_Pa();
    const double rho = mat.density_kg_m3;
    const bool rigid = mat.kind == materials::MaterialKind::Rigid;
    const bool shell = part.kind == model::ElementKind::Shell4;
    const std::size_t nn = shell ? 4 : 8;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* q = &part.connectivity[nn * e];
      bool mine = master[p] != 0;
      for (std::size_t a = 0; a < nn && !mine; ++a)
        mine = slave[static_cast<std::size_t>(q[a])] != 0;
      double share = 0.0;  // the element's lumped mass per node [kg]
      if (shell) {
        const double A = segment_area(x0, q);
        const double k = shell_stiffness(penalty_scale, K, A, segment_max_diagonal(x0, q));
        const bool tri = q[3] == q[2];
        // (the element's density rho s with mass scaling, as the solver's lumped mass)
        share = rho * part.density_scale_of(e) * part.thickness_of(e) * A / (tri ? 3.0 : 4.0);
        for (std::size_t a = 0; a < (tri ? 3u : 4u); ++a) {
          const auto i = static_cast<std::size_t>(q[a]);
          if (!mine) continue;
          np.half_thickness_m[i] = std::max(np.half_thickness_m[i], 0.5 * part.thickness_of(e));
          if (!rigid) np.stiffness_N_m[i] = std::max(np.stiffness_N_m[i], k);
          np.mass_kg[i] += share;
        }
        continue;
      }
      const double V = hex_volume(x0, q);
      share = rho * part.density_scale_of(e) * V / 8.0;
      double A = 0.0;
      for (const auto& f : kHexFaces) {
        const std::int32_t fq[4] = {q[f[0]], q[f[1]], q[f[2]], q[f[3]]};
        A += segment_area(x0, fq) / 6.0;
      }
      const double k = solid_face_stiffness(penalty_scale, K, A, V);
      for (std::size_t a = 0; a < 8; ++a) {
        const auto i = static_cast<std::size_t>(q[a]);
        if (!mine) continue;
        if (!rigid) np.stiffness_N_m[i] = std::max(np.stiffness_N_m[i], k);
        np.mass_kg[i] += share;
      }
    }
  }
  // A node with no element of the contact here (a `paper` copy, its elements in its owner's
  // domain): the solver's mass.
  for (std::size_t i = 0; i < n; ++i)
    if (!(np.mass_kg[i] > 0.0) && mass) np.mass_kg[i] = mass[i];
  for (const auto& rb : m.rigid_bodies) {
    std::vector<std::int32_t> nodes;
    for (int p : rb.parts) {
      const auto& conn = m.parts[static_cast<std::size_t>(p)].connectivity;
      nodes.insert(nodes.end(), conn.begin(), conn.end());
    }
    nodes.insert(nodes.end(), rb.nodes.begin(), rb.nodes.end());  // its extra nodes
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    double body = rb.mass_kg;
    if (!(body > 0.0)) {
      body = 0.0;
      for (auto i : nodes) body += mass ? mass[static_cast<std::size_t>(i)] : 0.0;
    }
    for (auto i : nodes) np.mass_kg[static_cast<std::size_t>(i)] = body;
  }
  np.unfixed_mass_kg = np.mass_kg;
  if (!m.fixed.empty())
    for (std::size_t i = 0; i < n; ++i)
      if ((m.fixed[i] & 7u) == 7u) np.mass_kg[i] = std::numeric_limits<double>::infinity();
  return np;
}

}  // namespace crashlink::contact
