#pragma once
// Issue 21, acceptance item 2: a thin-walled square steel tube crushed axially by a rigid mass
// (the classical crash-box test). Builder and a brute-force self-penetration checker.
//
// Tube: square section of mid-surface width C, wall t, length L along +z from z = 0 (clamped: all
// six dofs of the z = 0 ring) to z = L (struck). Shell4, J2 steel (test_models.h j2_steel), the
// quads' normals pointing out of the tube. The mesh is a ring of 4 C / h_around nodes repeated at
// every axial level: coarse levels (h_axial) from z = 0, then fine levels (h_fine) over the last
// fine_length near the struck end, the same nodes around, so the two parts share the ring at
// their junction (a conforming mesh; the fine part is where the tube folds first).
// Trigger: the classical square-tube folding mode (two opposite walls in, the other two out, a
// half sine across each wall and along the first half-wavelength H = 0.99 t^(1/3) C^(2/3) from
// the struck end: Wierzbicki & Abramowicz 1983), of amplitude trigger_m, so that the folds start
// at the struck end and the pattern does not hang on round-off.
// Ram: a rigid square shell plate (rigid body of mass ram_mass_kg) just above the struck end,
// at ram_speed_m_s along -z.
// Contacts: "ram" (tube nodes against the ram's segments, ram_kind), and SingleSurface over the
// tube ("self"; with domains, one per domain, "self_fine" and "self_coarse", since the
// decomposition wants each contact's master parts in one domain: solver/partition/analysis.cpp).
// Domains (multi): "fine" = {fine tube part, ram}, "coarse" = {coarse tube part}.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"
#include "tests/integration/test_models.h"

namespace crashlink::testing {

struct TubeSpec {
  double width_m = 0.05;        ///< C, mid-surface
  double thickness_m = 1.5e-3;  ///< t
  double length_m = 0.2;        ///< L
  double h_around_m = 5e-3;     ///< element size around the section (C / h_around an integer)
  double h_axial_m = 5e-3;      ///< coarse part's element length
  double fine_length_m = 0.06;  ///< 0: no fine part
  double h_fine_m = 2e-3;       ///< fine part's element length
  double trigger_m = 0.15e-3;   ///< imperfection amplitude (0: a perfect tube)
  double ram_mass_kg = 50.0;
  double ram_speed_m_s = 10.0;
  double ram_gap_m = 1e-4;  ///< between the offset surfaces at t = 0
  model::ContactKind ram_kind = model::ContactKind::NodeToSurface;
  bool self_contact = true;
  bool domains = false;
  double end_time_s = 3e-3;
};

struct Tube {
  model::Model m;
  std::vector<int> tube_parts;  ///< part indices of the tube (coarse first)
  int ram_part = -1;
  std::size_t tube_nodes = 0;      ///< tube nodes are [0, tube_nodes)
  double half_wavelength_m = 0.0;  ///< H of the trigger
};

/// The W-A half-wavelength of a square tube's fold, H = 0.99 t^(1/3) C^(2/3) (Wierzbicki &
/// Abramowicz, J. Appl. Mech. 50 (1983) 727-734).
inline double fold_half_wavelength(double t, double C) {
  return 0.99 * std::cbrt(t) * std::cbrt(C * C);
}

inline Tube make_tube(const TubeSpec& s) {
  Tube b;
  auto& m = b.m;
  m.name = "square tube crush";
  m.materials.push_back(j2_steel());
  m.materials.push_back({"rigid", materials::MaterialKind::Rigid, 7850.0, 210e9, 0.3, {}});
  const double C = s.width_m, L = s.length_m;
  const int per_side = static_cast<int>(std::lround(C / s.h_around_m));
  const int around = 4 * per_side;
  // axial levels: coarse from 0 to L - fine_length, then fine to L
  const double Lc = L - s.fine_length_m;
  std::vector<double> z;
  const int nc = static_cast<int>(std::lround(Lc / s.h_axial_m));
  for (int k = 0; k <= nc; ++k) z.push_back(Lc * k / nc);
  const std::size_t junction = z.size() - 1;  // level index where the fine part starts
  if (s.fine_length_m > 0.0) {
    const int nf = static_cast<int>(std::lround(s.fine_length_m / s.h_fine_m));
    for (int k = 1; k <= nf; ++k) z.push_back(Lc + s.fine_length_m * k / nf);
  }
  b.half_wavelength_m = fold_half_wavelength(s.thickness_m, C);
  const double H = b.half_wavelength_m;
  // ring: counter-clockwise seen from +z, starting at corner (-C/2, -C/2); wall w runs along
  // direction d_w with outward normal o_w
  const std::array<Vec3, 4> corner{
      {{-C / 2, -C / 2, 0}, {C / 2, -C / 2, 0}, {C / 2, C / 2, 0}, {-C / 2, C / 2, 0}}};
  const std::array<Vec3, 4> outward{{{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}}};
  std::int64_t id = next_node_id(m);
  for (double zk : z)
    for (int w = 0; w < 4; ++w)
      for (int j = 0; j < per_side; ++j) {
        const double f = static_cast<double>(j) / per_side;
        Vec3 x = corner[static_cast<std::size_t>(w)] +
                 f * (corner[static_cast<std::size_t>((w + 1) % 4)] -
                      corner[static_cast<std::size_t>(w)]);
        x[2] = zk;
        const double from_top = L - zk;
        if (s.trigger_m > 0.0 && from_top < H) {
          const double sign = (w % 2 == 0) ? -1.0 : 1.0;  // walls 0, 2 in; 1, 3 out
          x = x + (sign * s.trigger_m * std::sin(M_PI * f) * std::sin(M_PI * from_top / H)) *
                      outward[static_cast<std::size_t>(w)];
        }
        m.nodes.id.push_back(id++);
        m.nodes.x0.insert(m.nodes.x0.end(), x.begin(), x.end());
      }
  b.tube_nodes = m.nodes.count();
  const auto node = [&](std::size_t level, int j) {
    return static_cast<std::int32_t>(level * static_cast<std::size_t>(around) +
                                     static_cast<std::size_t>((j + around) % around));
  };
  const auto tube_part = [&](const std::string& name, std::size_t k0, std::size_t k1) {
    model::Part p;
    p.name = name;
    p.kind = model::ElementKind::Shell4;
    p.material = 0;
    p.thickness_m = s.thickness_m;
    p.through_thickness_points = 5;
    for (std::size_t k = k0; k < k1; ++k)
      for (int j = 0; j < around; ++j)  // counter-clockwise ring x +z: outward normal
        for (auto c : {node(k, j), node(k, j + 1), node(k + 1, j + 1), node(k + 1, j)})
          p.connectivity.push_back(c);
    b.tube_parts.push_back(model::append_part(m, p));
  };
  tube_part(s.fine_length_m > 0.0 ? "tube_coarse" : "tube", 0, junction);
  if (s.fine_length_m > 0.0) tube_part("tube_fine", junction, z.size() - 1);
  // ram: 80 x 80 mm rigid plate, 8 x 8 quads, 2 mm thick (contact offset only)
  const double ram_t = 2e-3, ram_side = 0.08;
  const double zr = L + 0.5 * (s.thickness_m + ram_t) + s.ram_gap_m;
  model::Part ram;
  ram.name = "ram";
  ram.material = 1;
  ram.thickness_m = ram_t;
  b.ram_part = model::generate_plate(m, ram,
                                     {{-ram_side / 2, -ram_side / 2, zr},
                                      {ram_side, 0.0, 0.0},
                                      {0.0, ram_side, 0.0},
                                      {8, 8},
                                      0.0});
  m.fixed.assign(m.nodes.count(), 0);
  for (int j = 0; j < around; ++j) m.fixed[static_cast<std::size_t>(node(0, j))] = 63;
  model::RigidBody rb;
  rb.name = "ram";
  rb.parts = {b.ram_part};
  rb.velocity_m_s = {0.0, 0.0, -s.ram_speed_m_s};
  rb.mass_kg = s.ram_mass_kg;
  // inertia of a steel block 100 x 100 mm of that mass: it barely tilts
  const double J = s.ram_mass_kg * (0.1 * 0.1 + 0.1 * 0.1) / 12.0;
  rb.inertia_given = true;
  rb.inertia_kg_m2 = {{{J, 0.0, 0.0}, {0.0, J, 0.0}, {0.0, 0.0, J}}};
  rb.centre_given = true;
  rb.centre_m = {0.0, 0.0, zr};
  m.rigid_bodies.push_back(rb);
  model::Contact ram_c;
  ram_c.name = "ram";
  ram_c.kind = s.ram_kind;
  for (std::size_t i = 0; i < b.tube_nodes; ++i)
    // multi: the fine part's nodes above the junction ring (which the coarse part holds too:
    // the decomposition would move the coarse elements around a slave node into the contact's
    // domain)
    if (!s.domains || m.nodes.x0[3 * i + 2] > z[junction] + 1e-9)
      ram_c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  ram_c.master_parts = {b.ram_part};
  m.contacts.push_back(ram_c);
  if (s.self_contact) {
    if (s.domains && b.tube_parts.size() == 2) {
      for (std::size_t p = 0; p < 2; ++p) {
        model::Contact c;
        c.name = p == 0 ? "self_coarse" : "self_fine";
        c.kind = model::ContactKind::SingleSurface;
        c.master_parts = {b.tube_parts[p]};
        m.contacts.push_back(c);
      }
    } else {
      model::Contact c;
      c.name = "self";
      c.kind = model::ContactKind::SingleSurface;
      c.master_parts = b.tube_parts;
      m.contacts.push_back(c);
    }
  }
  if (s.domains && b.tube_parts.size() == 2)
    m.domains = {{"coarse", {b.tube_parts[0]}}, {"fine", {b.tube_parts[1], b.ram_part}}};
  m.controls.end_time_s = s.end_time_s;
  return b;
}

// ---- self-penetration checker ----

/// Closest distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision Detection
/// (2005), 5.1.5).
inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return norm(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return norm(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return norm(p - (a + (d1 / (d1 - d3)) * ab));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return norm(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return norm(p - (a + (d2 / (d2 - d6)) * ac));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return norm(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));
  const double den = 1.0 / (va + vb + vc);
  return norm(p - (a + (vb * den) * ab + (vc * den) * ac));
}

/// Brute force over a hash grid: for every tube node and every tube segment that is neither one
/// of the node's own segments nor a neighbour of them (sharing a node with one: the 4 x 4 block
/// of quads around an interior node, what a single-surface contact excludes), the distance d from
/// the node to the segment (the quad as its two triangles for either diagonal, the nearer); the
/// penetration is t - d (both mid-surfaces carry a t/2 offset). A node that passed right through a
/// wall shows first as a penetration of nearly t: the caller samples often enough (the relative
/// travel between samples a small fraction of t).
class SelfPenetrationChecker {
 public:
  SelfPenetrationChecker(const model::Model& m, const std::vector<int>& parts, double thickness)
      : t_(thickness) {
    for (int p : parts) {
      const auto& c = m.parts[static_cast<std::size_t>(p)].connectivity;
      seg_.insert(seg_.end(), c.begin(), c.end());
    }
    const std::size_t ns = seg_.size() / 4;
    std::unordered_map<std::int32_t, std::vector<std::int32_t>> node_segs;
    for (std::size_t e = 0; e < ns; ++e)
      for (int a = 0; a < 4; ++a)
        node_segs[seg_[4 * e + a]].push_back(static_cast<std::int32_t>(e));
    for (const auto& [n, own] : node_segs) {
      std::vector<std::int32_t> ex;
      for (auto e : own)
        for (int a = 0; a < 4; ++a) {
          const auto& near = node_segs[seg_[4 * static_cast<std::size_t>(e) + a]];
          ex.insert(ex.end(), near.begin(), near.end());
        }
      std::sort(ex.begin(), ex.end());
      ex.erase(std::unique(ex.begin(), ex.end()), ex.end());
      excluded_[n] = std::move(ex);
      nodes_.push_back(n);
    }
    std::sort(nodes_.begin(), nodes_.end());
  }

  struct Result {
    double penetration_m = 0.0;  ///< max of t - d over the pairs; -t: no pair within t
    std::int32_t node = -1, segment = -1;
    std::size_t pairs = 0;  ///< node-segment pairs with d < t
  };

  /// x: current coordinates [3n] of every model node.
  Result check(const double* x) const {
    const std::size_t ns = seg_.size() / 4;
    // grid of cell size = the largest inflated segment box edge
    std::vector<std::array<double, 6>> box(ns);
    double cell = 0.0;
    for (std::size_t e = 0; e < ns; ++e) {
      auto& bx = box[e];
      bx = {1e30, 1e30, 1e30, -1e30, -1e30, -1e30};
      for (int a = 0; a < 4; ++a) {
        const double* p = x + 3 * static_cast<std::size_t>(seg_[4 * e + a]);
        for (int d = 0; d < 3; ++d) {
          bx[d] = std::min(bx[d], p[d] - t_);
          bx[3 + d] = std::max(bx[3 + d], p[d] + t_);
        }
      }
      for (int d = 0; d < 3; ++d) cell = std::max(cell, bx[3 + d] - bx[d]);
    }
    const auto key = [&](double a, double b, double c) {
      const auto i = static_cast<std::int64_t>(std::floor(a / cell)) & 0x1FFFFF;
      const auto j = static_cast<std::int64_t>(std::floor(b / cell)) & 0x1FFFFF;
      const auto k = static_cast<std::int64_t>(std::floor(c / cell)) & 0x1FFFFF;
      return (i << 42) | (j << 21) | k;
    };
    std::unordered_map<std::int64_t, std::vector<std::int32_t>> grid;
    for (std::size_t e = 0; e < ns; ++e) {
      const auto& bx = box[e];
      // the box spans at most two cells per axis (edge <= cell)
      for (double a : {bx[0], bx[3]})
        for (double b : {bx[1], bx[4]})
          for (double c : {bx[2], bx[5]}) {
            auto& v = grid[key(a, b, c)];
            if (v.empty() || v.back() != static_cast<std::int32_t>(e))
              v.push_back(static_cast<std::int32_t>(e));
          }
    }
    for (auto& [k, v] : grid) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    }
    Result r;
    r.penetration_m = -t_;
    for (auto n : nodes_) {
      const double* pn = x + 3 * static_cast<std::size_t>(n);
      const Vec3 p{pn[0], pn[1], pn[2]};
      const auto it = grid.find(key(p[0], p[1], p[2]));
      if (it == grid.end()) continue;
      const auto& ex = excluded_.at(n);
      for (auto e : it->second) {
        const auto& bx = box[static_cast<std::size_t>(e)];
        if (p[0] < bx[0] || p[1] < bx[1] || p[2] < bx[2] || p[0] > bx[3] || p[1] > bx[4] ||
            p[2] > bx[5])
          continue;
        if (std::binary_search(ex.begin(), ex.end(), e)) continue;
        Vec3 q[4];
        for (int a = 0; a < 4; ++a) {
          const double* pa =
              x + 3 * static_cast<std::size_t>(seg_[4 * static_cast<std::size_t>(e) + a]);
          q[a] = {pa[0], pa[1], pa[2]};
        }
        const double d02 = std::min(point_triangle_distance(p, q[0], q[1], q[2]),
                                    point_triangle_distance(p, q[0], q[2], q[3]));
        const double d13 = std::min(point_triangle_distance(p, q[0], q[1], q[3]),
                                    point_triangle_distance(p, q[1], q[2], q[3]));
        const double d = std::min(d02, d13);
        if (d < t_) ++r.pairs;
        if (t_ - d > r.penetration_m) r.penetration_m = t_ - d, r.node = n, r.segment = e;
      }
    }
    return r;
  }

 private:
  double t_;
  std::vector<std::int32_t> seg_;  ///< [4 ns]
  std::vector<std::int32_t> nodes_;
  std::unordered_map<std::int32_t, std::vector<std::int32_t>> excluded_;
};

}  // namespace crashlink::testing
