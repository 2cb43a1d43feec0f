#include "solver/contact/segments.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/errors.h"

namespace crashlink::contact {

namespace {

Vec3 node(const double* x, std::int32_t i) {
  const auto k = 3 * static_cast<std::size_t>(i);
  return {x[k], x[k + 1], x[k + 2]};
}

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(b - a, cross(c - a, d - a)) / 6.0;
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

namespace {

/// One face of an element: a shell element itself, or one of a hexahedron's six faces.
struct FaceRef {
  std::array<std::int32_t, 4> key;  ///< sorted node indices
  std::uint32_t part, element;
  std::uint8_t face;  ///< hex face (kHexFaces), 255 for a shell
};

/// Every shell element and every hexahedron face of the model, sorted by key (then part,
/// element): a hexahedron face whose key appears once is exterior.
std::vector<FaceRef> model_faces(const model::Model& m, bool with_shells) {
  std::vector<FaceRef> faces;
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const auto& part = m.parts[p];
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (part.kind == model::ElementKind::Shell4) {
        if (!with_shells) continue;
        FaceRef r{};
        for (int a = 0; a < 4; ++a)
          r.key[static_cast<std::size_t>(a)] =
              part.connectivity[4 * e + static_cast<std::size_t>(a)];
        std::sort(r.key.begin(), r.key.end());
        r.part = static_cast<std::uint32_t>(p);
        r.element = static_cast<std::uint32_t>(e);
        r.face = 255;
        faces.push_back(r);
        continue;
      }
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
  }
  std::sort(faces.begin(), faces.end(), [](const FaceRef& a, const FaceRef& b) {
    if (a.key != b.key) return a.key < b.key;
    if (a.part != b.part) return a.part < b.part;
    return a.element < b.element;
  });
  return faces;
}

/// The face's nodes in element order (hex faces: outward normal).
std::array<std::int32_t, 4> face_nodes(const model::Model& m, const FaceRef& f) {
  const auto& part = m.parts[f.part];
  std::array<std::int32_t, 4> q{};
  if (f.face == 255) {
    for (int a = 0; a < 4; ++a)
      q[static_cast<std::size_t>(a)] =
          part.connectivity[4 * f.element + static_cast<std::size_t>(a)];
  } else {
    const std::int32_t* conn = &part.connectivity[8 * static_cast<std::size_t>(f.element)];
    for (int a = 0; a < 4; ++a) q[static_cast<std::size_t>(a)] = conn[kHexFaces[f.face][a]];
  }
  return q;
}

/// Appends face f (nodes q) to the set with its offset (shells t/2), depth (hex faces V / (2 A),
/// half the element's thickness) and stiffness (shell_stiffness, solid_face_stiffness).
void push_face(const model::Model& m, const FaceRef& f, const std::array<std::int32_t, 4>& q,
               double penalty_scale, SegmentSet& s) {
  const double* x0 = m.nodes.x0.data();
  const auto& part = m.parts[f.part];
  const double K = m.materials[static_cast<std::size_t>(part.material)].bulk_modulus_Pa();
  const bool rigid = is_rigid(m, part);
  const double A = segment_area(x0, q.data());
  double k = 0.0, offset = 0.0, depth = 0.0;
  const bool shell = f.face == 255;
  if (shell) {
    k = shell_stiffness(penalty_scale, K, A, segment_max_diagonal(x0, q.data()));
    offset = 0.5 * part.thickness_of(static_cast<std::size_t>(f.element));
  } else {
    const double V = hex_volume(x0, &part.connectivity[8 * static_cast<std::size_t>(f.element)]);
    k = solid_face_stiffness(penalty_scale, K, A, V);
    depth = 0.5 * V / A;
  }
  s.nodes.insert(s.nodes.end(), q.begin(), q.end());
  s.offset_m.push_back(offset);
  s.depth_m.push_back(depth);
  s.stiffness_N_m.push_back(rigid ? 0.0 : k);
  s.rigid_stiffness_N_m.push_back(k);
  s.two_sided.push_back(shell ? 1 : 0);
  s.rigid.push_back(rigid ? 1 : 0);
}

}  // namespace

SegmentSet build_segments(const model::Model& m, const std::vector<int>& master_parts,
                          double penalty_scale) {
  SegmentSet s;
  std::vector<std::uint8_t> is_master(m.parts.size(), 0);
  bool any_hex = false;
  for (int p : master_parts) {
    if (p < 0 || static_cast<std::size_t>(p) >= m.parts.size())
      throw ModelError(
          fmt::format("contact master part index {} is out of range (the model has {} "
                      "parts)",
                      p, m.parts.size()));
    is_master[static_cast<std::size_t>(p)] = 1;
    any_hex = any_hex || m.parts[static_cast<std::size_t>(p)].kind == model::ElementKind::Hex8;
  }
  // Shells: every element of a master part, in part and element order.
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const auto& part = m.parts[p];
    if (!is_master[p] || part.kind != model::ElementKind::Shell4) continue;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const FaceRef f{{}, static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(e), 255};
      push_face(m, f, face_nodes(m, f), penalty_scale, s);
    }
  }
  // Hexahedra: faces used by exactly one Hex8 of the whole model.
  if (any_hex) {
    const auto faces = model_faces(m, false);
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j].key == faces[i].key) ++j;
      if (j == i + 1 && is_master[faces[i].part])
        push_face(m, faces[i], face_nodes(m, faces[i]), penalty_scale, s);
      i = j;
    }
  }
  if (s.size() == 0)
    throw ModelError(
        "contact master parts give no segment (no shell element and no exterior "
        "hexahedron face); list the parts whose surface the slave nodes hit");
  return s;
}

std::vector<std::int32_t> slave_faces(const model::Model& m, const std::vector<std::int32_t>& nodes,
                                      const std::vector<int>& master_parts) {
  std::vector<std::uint8_t> in(m.nodes.count(), 0);
  for (auto i : nodes)
    if (i >= 0 && static_cast<std::size_t>(i) < in.size()) in[static_cast<std::size_t>(i)] = 1;
  // nodes of the master parts' elements: a face holding one is glued to the master side
  std::vector<std::uint8_t> master(m.nodes.count(), 0);
  for (int p : master_parts)
    if (p >= 0 && static_cast<std::size_t>(p) < m.parts.size())
      for (auto i : m.parts[static_cast<std::size_t>(p)].connectivity)
        master[static_cast<std::size_t>(i)] = 1;
  const auto faces = model_faces(m, true);
  const auto count_in = [&](const FaceRef& f) {
    int n = 0;
    for (auto k : f.key) n += in[static_cast<std::size_t>(k)];
    return n;
  };
  const auto exterior = [&](std::size_t i) {
    return (i == 0 || faces[i - 1].key != faces[i].key) &&
           (i + 1 == faces.size() || faces[i + 1].key != faces[i].key);
  };
  // hexahedra with an exterior face made of slave nodes: the first row along the slave face
  const auto elem_key = [](const FaceRef& f) {
    return (static_cast<std::uint64_t>(f.part) << 32) | f.element;
  };
  std::vector<std::uint64_t> row;
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (faces[i].face != 255 && exterior(i) && count_in(faces[i]) == 4)
      row.push_back(elem_key(faces[i]));
  std::sort(row.begin(), row.end());
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    const FaceRef& f = faces[i];
    const int n_in = count_in(f);
    bool glued = false;
    for (auto k : f.key) glued = glued || master[static_cast<std::size_t>(k)];
    const bool shell = f.face == 255;
    // a shell element with all four nodes in; an exterior hexahedron face (used once) with all
    // four in, or with some in, of an element of the first row along the slave face, and none
    // on the master side (the side faces along the slave face's edges: a tilted face's edge then
    // meets a surface, not a gap between two; a neighbouring part glued to the slave part's
    // nodes gives none)
    const bool side = n_in > 0 && !glued && std::binary_search(row.begin(), row.end(), elem_key(f));
    const bool take = shell ? n_in == 4 : (j == i + 1 && (n_in == 4 || side));
    if (take) {
      const auto q = face_nodes(m, f);
      out.insert(out.end(), q.begin(), q.end());
    }
    i = j;
  }
  return out;
}

SegmentSet build_faces(const model::Model& m, const std::vector<std::int32_t>& faces,
                       double penalty_scale) {
  SegmentSet s;
  if (faces.empty()) return s;
  const auto all = model_faces(m, true);
  for (std::size_t k = 0; k + 3 < faces.size(); k += 4) {
    std::array<std::int32_t, 4> q{faces[k], faces[k + 1], faces[k + 2], faces[k + 3]};
    FaceRef probe{};
    probe.key = q;
    std::sort(probe.key.begin(), probe.key.end());
    auto it = std::lower_bound(all.begin(), all.end(), probe,
                               [](const FaceRef& a, const FaceRef& b) { return a.key < b.key; });
    // the element whose face has this orientation (a cut model may hold only one of two hexes)
    const FaceRef* found = nullptr;
    for (; it != all.end() && it->key == probe.key; ++it)
      if (face_nodes(m, *it) == q || it->face == 255) {
        found = &*it;
        break;
      }
    if (!found) {
      const auto id = [&](std::int32_t i) { return m.nodes.id[static_cast<std::size_t>(i)]; };
      throw ModelError(fmt::format(
          "contact face with node ids {} {} {} {} belongs to no element of this model (internal "
          "error: slave faces are taken from the model's elements)",
          id(q[0]), id(q[1]), id(q[2]), id(q[3])));
    }
    push_face(m, *found, q, penalty_scale, s);
  }
  return s;
}

}  // namespace crashlink::contact
