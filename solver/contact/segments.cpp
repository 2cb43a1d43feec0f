#include "solver/contact/segments.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/core/errors.h"

namespace crashlink::contact {

namespace {

Vec3 node(const double* x, std::int32_t i) {
  const auto k = 3 * static_cast<std::size_t>(i);
  return {x[k], x[k + 1], x[k + 2]};
}

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(b - a, cross(c - a, d - a)) / 6.0;
}

bool is_rigid(const model::Model& m, const model::Part& p) {
  return m.materials[static_cast<std::size_t>(p.material)].kind == materials::MaterialKind::Rigid;
}

}  // namespace

double solid_face_stiffness(double s, double K, double A, double V) {
  return s * K * A * A / V;
}
double shell_stiffness(double s, double K, double A, double max_diagonal) {
  return s * K * A / max_diagonal;
}

double hex_volume(const double* x, const std::int32_t* conn) {
  Vec3 p[8];
  for (int a = 0; a < 8; ++a) p[a] = node(x, conn[a]);
  static constexpr int kTets[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
  double v = 0.0;
  for (const auto& t : kTets) v += tet_volume(p[0], p[t[0]], p[t[1]], p[6]);
  return std::fabs(v);
}

double segment_area(const double* x, const std::int32_t* q) {
  const Vec3 a = node(x, q[0]), b = node(x, q[1]), c = node(x, q[2]), d = node(x, q[3]);
  if (q[3] == q[2]) return 0.5 * norm(cross(b - a, c - a));
  return 0.5 * norm(cross(c - a, d - b));
}

double segment_max_diagonal(const double* x, const std::int32_t* q) {
  const Vec3 a = node(x, q[0]), b = node(x, q[1]), c = node(x, q[2]), d = node(x, q[3]);
  if (q[3] == q[2]) return std::max({norm(b - a), norm(c - b), norm(a - c)});
  return std::max(norm(c - a), norm(d - b));
}

SegmentSet build_segments(const model::Model& m, const std::vector<int>& master_parts,
                          double penalty_scale) {
  SegmentSet s;
  const double* x0 = m.nodes.x0.data();
  std::vector<std::uint8_t> is_master(m.parts.size(), 0);
  for (int p : master_parts) {
    if (p < 0 || static_cast<std::size_t>(p) >= m.parts.size())
      throw ModelError(
          fmt::format("contact master part index {} is out of range (the model has {} "
                      "parts)",
                      p, m.parts.size()));
    is_master[static_cast<std::size_t>(p)] = 1;
  }
  auto push = [&](const std::array<std::int32_t, 4>& q, double offset, double depth, double k,
                  double k_rigid, bool two_sided, bool rigid) {
    s.nodes.insert(s.nodes.end(), q.begin(), q.end());
    s.offset_m.push_back(offset);
    s.depth_m.push_back(depth);
    s.stiffness_N_m.push_back(rigid ? 0.0 : k);
    s.rigid_stiffness_N_m.push_back(k_rigid);
    s.two_sided.push_back(two_sided ? 1 : 0);
    s.rigid.push_back(rigid ? 1 : 0);
  };

  // Shells: every element of a master part.
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const auto& part = m.parts[p];
    if (!is_master[p] || part.kind != model::ElementKind::Shell4) continue;
    const double K = m.materials[static_cast<std::size_t>(part.material)].bulk_modulus_Pa();
    const bool rigid = is_rigid(m, part);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* c = &part.connectivity[4 * e];
      const double A = segment_area(x0, c);
      const double k = shell_stiffness(penalty_scale, K, A, segment_max_diagonal(x0, c));
      push({c[0], c[1], c[2], c[3]}, 0.5 * part.thickness_m, 0.0, k, k, true, rigid);
    }
  }

  // Hexahedra: faces used by exactly one Hex8 of the whole model (sorted node keys).
  struct FaceRef {
    std::array<std::int32_t, 4> key;
    std::uint32_t part, element;
    std::uint8_t face;
  };
  std::vector<FaceRef> faces;
  bool any_master_hex = false;
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    if (is_master[p] && m.parts[p].kind == model::ElementKind::Hex8) any_master_hex = true;
  if (any_master_hex) {
    for (std::size_t p = 0; p < m.parts.size(); ++p) {
      const auto& part = m.parts[p];
      if (part.kind != model::ElementKind::Hex8) continue;
      for (std::size_t e = 0; e < part.element_count(); ++e)
        for (std::uint8_t f = 0; f < 6; ++f) {
          FaceRef r{};
          for (int a = 0; a < 4; ++a)
            r.key[static_cast<std::size_t>(a)] =
                part.connectivity[8 * e + static_cast<std::size_t>(kHexFaces[f][a])];
          std::sort(r.key.begin(), r.key.end());
          r.part = static_cast<std::uint32_t>(p);
          r.element = static_cast<std::uint32_t>(e);
          r.face = f;
          faces.push_back(r);
        }
    }
    std::sort(faces.begin(), faces.end(), [](const FaceRef& a, const FaceRef& b) {
      if (a.key != b.key) return a.key < b.key;
      if (a.part != b.part) return a.part < b.part;
      return a.element < b.element;
    });
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j].key == faces[i].key) ++j;
      const FaceRef& f = faces[i];
      if (j == i + 1 && is_master[f.part]) {
        const auto& part = m.parts[f.part];
        const std::int32_t* conn = &part.connectivity[8 * static_cast<std::size_t>(f.element)];
        std::array<std::int32_t, 4> q{};
        for (int a = 0; a < 4; ++a) q[static_cast<std::size_t>(a)] = conn[kHexFaces[f.face][a]];
        const double K = m.materials[static_cast<std::size_t>(part.material)].bulk_modulus_Pa();
        const double A = segment_area(x0, q.data());
        const double V = hex_volume(x0, conn);
        const double k = solid_face_stiffness(penalty_scale, K, A, V);
        push(q, 0.0, 0.5 * V / A, k, k, false, is_rigid(m, part));
      }
      i = j;
    }
  }
  // Order segments spatially-agnostic but deterministic: as built (parts, then elements).
  if (s.size() == 0)
    throw ModelError(
        "contact master parts give no segment (no shell element and no exterior "
        "hexahedron face); list the parts whose surface the slave nodes hit");
  return s;
}

}  // namespace crashlink::contact
