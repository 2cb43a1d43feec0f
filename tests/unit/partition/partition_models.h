#pragma once
// Small models for the decomposition tests (tests/integration/test_models.h style), each with its
// `domains`, and the checks every decomposition must pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"
#include "solver/model/node_merging.h"
#include "solver/partition/decomposition.h"

namespace crashlink::testing {

inline materials::Material elastic(const std::string& name, double rho = 7850.0) {
  return {name, materials::MaterialKind::Elastic, rho, 210e9, 0.3, {}};
}
inline materials::Material rigid() {
  return {"rigid", materials::MaterialKind::Rigid, 7850.0, 210e9, 0.3, {}};
}

inline model::Part part(const std::string& name, int material, double thickness = 0.0) {
  model::Part p;
  p.name = name;
  p.material = material;
  p.thickness_m = thickness;
  return p;
}

/// Appends a box part and merges its nodes into the earlier ones; returns the part index.
inline int add_box(model::Model& m, model::Part p, const model::BoxMesh& b) {
  const std::size_t first = m.nodes.count();
  const int idx = model::generate_box(m, std::move(p), b);
  if (first > 0) model::merge_coincident_nodes(m, first, 1e-6);
  return idx;
}
inline int add_plate(model::Model& m, model::Part p, const model::PlateMesh& pm, bool merge) {
  const std::size_t first = m.nodes.count();
  const int idx = model::generate_plate(m, std::move(p), pm);
  if (merge && first > 0) model::merge_coincident_nodes(m, first, 1e-6);
  return idx;
}

inline std::vector<std::int32_t> where(const model::Model& m,
                                       const std::function<bool(double, double, double)>& pred) {
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (pred(m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]))
      out.push_back(static_cast<std::int32_t>(i));
  return out;
}

inline void finish(model::Model& m) {
  m.controls.end_time_s = 1e-3;
  if (m.fixed.size() != m.nodes.count()) m.fixed.assign(m.nodes.count(), 0);
}

/// A bar of hexes along x, section 0.2 x 0.2 m: part "coarse" (elements 0..9, 0.1 m long,
/// x in [0, 1]) and part "fine" (elements 10..19, 0.05 m, x in [1, 1.5]), one node plane shared
/// at x = 1. Domains in the given order. Fixed at x = 0, a load on the tip, an initial velocity,
/// probes at the tip and on the layer's far plane x = 0.9.
inline model::Model bar_two_sizes(bool fine_first = false) {
  model::Model m;
  m.name = "bar";
  m.materials.push_back(elastic("steel"));
  add_box(m, part("coarse", 0), {{0.0, -0.1, -0.1}, {1.0, 0.2, 0.2}, {10, 1, 1}});
  add_box(m, part("fine", 0), {{1.0, -0.1, -0.1}, {0.5, 0.2, 0.2}, {10, 1, 1}});
  finish(m);
  for (auto i : where(m, [](double x, double, double) { return x < 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] = 7;
  m.loads.push_back({"pull", where(m, [](double x, double, double) { return x > 1.5 - 1e-9; }), 0,
                     model::Curve::constant(1e3)});
  std::vector<std::int32_t> all(m.nodes.count());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::int32_t>(i);
  m.initial_velocities.push_back({all, {1.0, 0.0, 0.0}});
  m.probes.push_back({"tip", model::Probe::Kind::Node,
                      where(m, [](double x, double, double) { return x > 1.5 - 1e-9; })[0]});
  m.probes.push_back({"j", model::Probe::Kind::Node, where(m, [](double x, double, double) {
                        return std::abs(x - 0.9) < 1e-9;
                      })[0]});
  model::Domain coarse, fine;
  coarse.name = "coarse";
  coarse.parts = {0};
  fine.name = "fine";
  fine.parts = {1};
  if (fine_first) {
    m.domains.push_back(fine);
    m.domains.push_back(coarse);
  } else {
    m.domains.push_back(coarse);
    m.domains.push_back(fine);
  }
  return m;
}

/// A shell plate 1 x 1 m cut along x = 0.5: "left" 4 x 8 elements (0.125 m), "right" 8 x 8
/// (0.0625 x 0.125 m); 9 nodes shared on the cut.
inline model::Model plate_cut() {
  model::Model m;
  m.name = "plate";
  m.materials.push_back(elastic("steel"));
  add_plate(m, part("left", 0, 0.002), {{0, 0, 0}, {0.5, 0, 0}, {0, 1, 0}, {4, 8}, 0.0}, false);
  add_plate(m, part("right", 0, 0.002), {{0.5, 0, 0}, {0.5, 0, 0}, {0, 1, 0}, {8, 8}, 0.0}, true);
  finish(m);
  m.domains = {{"left", {0}}, {"right", {1}}};
  return m;
}

/// A hex block: "coarse" 2 x 2 x 2 elements of 0.5 m in x in [0, 1], "fine" 4 x 2 x 2 elements
/// (0.125 x 0.5 x 0.5 m) in x in [1, 1.5]; a 3 x 3 node face shared at x = 1.
inline model::Model hex_block() {
  model::Model m;
  m.name = "block";
  m.materials.push_back(elastic("steel"));
  add_box(m, part("coarse", 0), {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});
  add_box(m, part("fine", 0), {{1, 0, 0}, {0.5, 1, 1}, {4, 2, 2}});
  finish(m);
  m.domains = {{"coarse", {0}}, {"fine", {1}}};
  return m;
}

/// Three bars in a chain along x, section 0.4 x 0.4 m: "coarse" 5 x 0.2 m (x in [0, 1]), "mid"
/// 5 x 0.1 m ([1, 1.5]), "fine" 10 x 0.05 m ([1.5, 2]). Domains in the order given.
inline model::Model chain3(std::vector<model::Domain> domains = {
                               {"coarse", {0}}, {"mid", {1}}, {"fine", {2}}}) {
  model::Model m;
  m.name = "chain";
  m.materials.push_back(elastic("steel"));
  add_box(m, part("coarse", 0), {{0, -0.2, -0.2}, {1.0, 0.4, 0.4}, {5, 1, 1}});
  add_box(m, part("mid", 0), {{1.0, -0.2, -0.2}, {0.5, 0.4, 0.4}, {5, 1, 1}});
  add_box(m, part("fine", 0), {{1.5, -0.2, -0.2}, {0.5, 0.4, 0.4}, {10, 1, 1}});
  finish(m);
  m.domains = std::move(domains);
  return m;
}

/// chain3 held at x = 0, bulk viscosity on, run to `end_s`, with a triangular force pulse along x
/// on its x = 2 m end: 0 at t = 0, `peak_N` at `rise_s`, 0 from 2 `rise_s` on.
inline model::Model pulsed_chain3(std::vector<model::Domain> domains, double end_s, double rise_s,
                                  double peak_N) {
  auto m = chain3(std::move(domains));
  m.controls.end_time_s = end_s;
  m.controls.bulk_viscosity = true;
  for (auto i : where(m, [](double x, double, double) { return x < 1e-9; }))
    m.fixed[static_cast<std::size_t>(i)] |= 7;
  const auto end = where(m, [](double x, double, double) { return x > 2.0 - 1e-9; });
  m.loads.push_back({"pulse", end, 0, model::Curve{{0.0, rise_s, 2 * rise_s}, {0.0, peak_N, 0.0}}});
  return m;
}

/// Four 0.5 x 0.5 m quadrant plates (4 x 4 shells each) around the origin, same mesh, densities
/// 1, 4, 16 x steel so that the steps are in ratio 1 : 2 : 4: domain "a" = q1 (finest), "b" = q2,
/// "c" = q3 + q4 (coarsest). The centre node is shared by the three domains.
inline model::Model quadrants3() {
  model::Model m;
  m.name = "quadrants";
  m.materials = {elastic("a", 7850.0), elastic("b", 4 * 7850.0), elastic("c", 16 * 7850.0)};
  const double t = 0.002;
  add_plate(m, part("q1", 0, t), {{0, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, false);
  add_plate(m, part("q2", 1, t), {{-0.5, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, true);
  add_plate(m, part("q3", 2, t), {{-0.5, -0.5, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, true);
  add_plate(m, part("q4", 2, t), {{0, -0.5, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, true);
  finish(m);
  m.domains = {{"a", {0}}, {"b", {1}}, {"c", {2, 3}}};
  return m;
}

/// A rigid cube-sphere (radius 0.1 m, rigid body "head", its own domain) 5 mm above an elastic
/// plate 1 x 1 m (8 x 8 shells, domain "plate"), contact slave = plate nodes, master = the sphere;
/// a probe on the body.
inline model::Model sphere_over_plate() {
  model::Model m;
  m.name = "headform";
  m.materials = {elastic("steel"), rigid()};
  add_plate(m, part("plate", 0, 0.002), {{-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, {8, 8}, 0.0},
            false);
  model::generate_sphere(m, part("sphere", 1, 0.002), {{0, 0, 0.105}, 0.1, 4});
  finish(m);
  model::RigidBody rb;
  rb.name = "head";
  rb.parts = {1};
  rb.velocity_m_s = {0, 0, -5};
  m.rigid_bodies.push_back(rb);
  model::Contact c;
  c.name = "head_on_plate";
  c.slave_nodes = where(m, [](double, double, double z) { return std::abs(z) < 1e-9; });
  c.master_parts = {1};
  m.contacts.push_back(c);
  m.probes.push_back({"head", model::Probe::Kind::RigidBody, 0});
  m.domains = {{"plate", {0}}, {"head", {1}}};
  return m;
}

/// A small fine hex block (0.02 m elements, domain "block") above a coarse shell floor made of
/// "plate" (x in [0, 0.5], 4 x 4) and "frame" (x in [0.5, 1], 4 x 4, sharing the line x = 0.5),
/// domain "floor". Contact: slave = the block's nodes, master = plate. The plate (contact surface
/// of the coarse side) moves into the block's domain; J = the 5 nodes on the plate/frame line.
inline model::Model block_on_floor() {
  model::Model m;
  m.name = "block_on_floor";
  m.materials.push_back(elastic("steel"));
  add_plate(m, part("plate", 0, 0.002), {{0, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, false);
  add_plate(m, part("frame", 0, 0.002), {{0.5, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {4, 4}, 0.0}, true);
  const std::size_t first_block = m.nodes.count();
  model::generate_box(m, part("block", 0), {{0.2, 0.2, 0.002}, {0.06, 0.06, 0.04}, {3, 3, 2}});
  finish(m);
  model::Contact c;
  c.name = "block_on_plate";
  for (std::size_t i = first_block; i < m.nodes.count(); ++i)
    c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  c.master_parts = {0};
  m.contacts.push_back(c);
  m.domains = {{"floor", {0, 1}}, {"block", {2}}};
  return m;
}

/// A finely meshed elastic shell sphere (master, domain "ball") over a coarse plate 1 x 1 m
/// (8 x 8 shells of 0.125 m, domain "ground") whose slave nodes are the 9 central ones
/// (|x|, |y| <= 0.125): the slave side is coarse, so the 16 plate elements holding slave nodes move
/// into "ball" and J is the perimeter of [-0.25, 0.25]^2.
inline model::Model ball_on_ground() {
  model::Model m;
  m.name = "ball_on_ground";
  m.materials.push_back(elastic("steel"));
  add_plate(m, part("ground", 0, 0.002), {{-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, {8, 8}, 0.0},
            false);
  model::generate_sphere(m, part("ball", 0, 0.002), {{0, 0, 0.105}, 0.1, 6});
  finish(m);
  model::Contact c;
  c.name = "ball_on_ground";
  c.slave_nodes = where(m, [](double x, double y, double z) {
    return std::abs(z) < 1e-9 && std::abs(x) < 0.13 && std::abs(y) < 0.13;
  });
  c.master_parts = {1};
  m.contacts.push_back(c);
  m.domains = {{"ground", {0}}, {"ball", {1}}};
  return m;
}

/// Natural lumped nodal masses [n] by the solver's own element functions.
inline std::vector<double> lumped_mass(const model::Model& m) {
  std::vector<double> mass(m.nodes.count(), 0.0), inertia(m.nodes.count(), 0.0);
  for (const auto& p : m.parts) {
    const auto& mat = m.materials[static_cast<std::size_t>(p.material)];
    if (p.kind == model::ElementKind::Hex8)
      elements::hex8_lumped_mass(p, mat, m.nodes.x0.data(), mass.data());
    else
      elements::shell_lumped_mass(p, mat, m.nodes.x0.data(), mass.data(), inertia.data());
  }
  return mass;
}

inline double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

/// Domain index by name, -1 if none.
inline int domain_index(const partition::Decomposition& d, const std::string& name) {
  for (std::size_t k = 0; k < d.domains.size(); ++k)
    if (d.domains[k].name == name) return static_cast<int>(k);
  return -1;
}

/// The checks every decomposition passes (both schemes): each global element exactly once with
/// its id, nodes keep ids and coordinates, each sub-model validates, masses add up, J masses are
/// the global lumped masses, fine has the smaller step. Layer: every node non-ghost in exactly
/// one domain. Paper: nothing moves, link nodes present wherever used, copies carry no mass.
inline void check_invariants(const model::Model& g, const partition::Decomposition& d) {
  const auto scheme = d.scheme;
  const auto gm = lumped_mass(g);
  ASSERT_EQ(d.domain_dt_s.size(), d.domains.size());
  // Elements.
  std::map<std::pair<int, int>, int> seen;  // (global part, element) -> count
  for (const auto& dm : d.domains) {
    ASSERT_NO_THROW(model::validate(dm.model)) << dm.name;
    ASSERT_EQ(dm.part_global.size(), dm.model.parts.size());
    for (std::size_t p = 0; p < dm.model.parts.size(); ++p) {
      const auto& gp = g.parts[static_cast<std::size_t>(dm.part_global[p])];
      const auto& lp = dm.model.parts[p];
      EXPECT_EQ(lp.name, gp.name);
      ASSERT_EQ(lp.element_count(), dm.part_elements[p].size());
      const auto k = static_cast<std::size_t>(model::nodes_per_element(gp.kind));
      for (std::size_t e = 0; e < lp.element_count(); ++e) {
        const auto ge = static_cast<std::size_t>(dm.part_elements[p][e]);
        ++seen[{dm.part_global[p], static_cast<int>(ge)}];
        EXPECT_EQ(lp.element_id[e], gp.element_id[ge]);
        for (std::size_t j = 0; j < k; ++j)
          EXPECT_EQ(dm.global_node[static_cast<std::size_t>(lp.connectivity[k * e + j])],
                    gp.connectivity[k * ge + j]);
      }
    }
  }
  EXPECT_EQ(seen.size(), g.element_count());
  for (const auto& kv : seen) EXPECT_EQ(kv.second, 1) << "element appears more than once";
  // Nodes and masses.
  std::vector<int> nonghost(g.nodes.count(), 0), present(g.nodes.count(), 0);
  double total = 0.0;
  for (const auto& dm : d.domains) {
    const auto lm = lumped_mass(dm.model);
    const std::size_t nl = dm.global_node.size();
    ASSERT_EQ(dm.model.nodes.count(), nl);
    ASSERT_EQ(dm.ghost.size(), nl);
    ASSERT_EQ(dm.copy.size(), nl);
    ASSERT_EQ(dm.interface_mass_kg.size(), nl);
    EXPECT_TRUE(std::is_sorted(dm.global_node.begin(), dm.global_node.end()));
    for (std::size_t l = 0; l < nl; ++l) {
      const auto gi = static_cast<std::size_t>(dm.global_node[l]);
      EXPECT_EQ(dm.model.nodes.id[l], g.nodes.id[gi]);
      for (std::size_t c = 0; c < 3; ++c)
        EXPECT_EQ(dm.model.nodes.x0[3 * l + c], g.nodes.x0[3 * gi + c]);
      ++present[gi];
      if (dm.ghost[l]) {
        EXPECT_EQ(dm.interface_mass_kg[l], 0.0);
        continue;
      }
      ++nonghost[gi];
      if (dm.copy[l]) {
        EXPECT_EQ(lm[l], 0.0) << "a copy has no own mass";
      }
      if (dm.interface_mass_kg[l] > 0.0) {
        EXPECT_NEAR(dm.interface_mass_kg[l], gm[gi], 1e-12 * gm[gi]);
      }
      if (scheme == partition::Scheme::Layer) {
        total += dm.interface_mass_kg[l] > 0.0 ? dm.interface_mass_kg[l] : lm[l];
      } else {
        total += lm[l];  // partial masses add up to the whole (copies add 0)
      }
    }
  }
  EXPECT_NEAR(total, sum(gm), 1e-12 * sum(gm));
  for (std::size_t i = 0; i < g.nodes.count(); ++i) {
    EXPECT_GE(present[i], 1);
    if (scheme == partition::Scheme::Layer) {
      EXPECT_EQ(nonghost[i], 1) << "node " << g.nodes.id[i];
    }
  }
  // Interfaces.
  for (const auto& itf : d.interfaces) {
    ASSERT_GE(itf.fine, 0);
    ASSERT_GE(itf.coarse, 0);
    EXPECT_NE(itf.fine, itf.coarse);
    EXPECT_LE(d.domain_dt_s[static_cast<std::size_t>(itf.fine)],
              d.domain_dt_s[static_cast<std::size_t>(itf.coarse)]);
    ASSERT_EQ(itf.j_mass_kg.size(), itf.j_nodes_global.size());
    for (std::size_t j = 0; j < itf.j_nodes_global.size(); ++j) {
      const auto gi = static_cast<std::size_t>(itf.j_nodes_global[j]);
      EXPECT_NEAR(itf.j_mass_kg[j], gm[gi], 1e-12 * gm[gi]);
    }
    if (scheme == partition::Scheme::Layer) {
      EXPECT_EQ(itf.reference, itf.coarse);
      // J: a ghost in fine, owned with the summed mass in coarse.
      const auto& f = d.domains[static_cast<std::size_t>(itf.fine)];
      const auto& c = d.domains[static_cast<std::size_t>(itf.coarse)];
      for (std::size_t j = 0; j < itf.j_nodes_global.size(); ++j) {
        const auto gi = itf.j_nodes_global[j];
        const auto lf = std::lower_bound(f.global_node.begin(), f.global_node.end(), gi) -
                        f.global_node.begin();
        const auto lc = std::lower_bound(c.global_node.begin(), c.global_node.end(), gi) -
                        c.global_node.begin();
        ASSERT_LT(static_cast<std::size_t>(lf), f.global_node.size());
        ASSERT_LT(static_cast<std::size_t>(lc), c.global_node.size());
        EXPECT_EQ(f.global_node[static_cast<std::size_t>(lf)], gi);
        EXPECT_EQ(c.global_node[static_cast<std::size_t>(lc)], gi);
        EXPECT_EQ(f.ghost[static_cast<std::size_t>(lf)], 1);
        EXPECT_EQ(c.ghost[static_cast<std::size_t>(lc)], 0);
        EXPECT_EQ(c.interface_mass_kg[static_cast<std::size_t>(lc)], itf.j_mass_kg[j]);
      }
    } else {
      EXPECT_TRUE(itf.moved_elements.empty());
    }
  }
  // Contacts: each in exactly one domain; probes each in exactly one domain.
  std::map<std::string, int> contacts, probes;
  for (const auto& dm : d.domains) {
    for (const auto& c : dm.model.contacts) ++contacts[c.name];
    for (const auto& p : dm.model.probes) ++probes[p.name];
  }
  EXPECT_EQ(contacts.size(), g.contacts.size());
  for (const auto& kv : contacts) EXPECT_EQ(kv.second, 1) << kv.first;
  EXPECT_EQ(probes.size(), g.probes.size());
  for (const auto& kv : probes) EXPECT_EQ(kv.second, 1) << kv.first;
}

/// The local index of global node gi in domain dm, or -1.
inline int local_of(const partition::DomainModel& dm, std::int32_t gi) {
  const auto it = std::lower_bound(dm.global_node.begin(), dm.global_node.end(), gi);
  if (it == dm.global_node.end() || *it != gi) return -1;
  return static_cast<int>(it - dm.global_node.begin());
}

/// The coupling study's Hann velocity pulse: 0.5 v0 (1 - cos(2 pi t / tp)) [m/s] over [0, tp] in
/// 100 segments, then 0 until `hold_s`.
inline model::Curve hann_pulse(double tp_s, double v0_m_s, double hold_s) {
  model::Curve hann;
  for (int k = 0; k <= 100; ++k) {
    const double t = tp_s * k / 100.0;
    hann.t_s.push_back(t);
    hann.value.push_back(0.5 * v0_m_s * (1.0 - std::cos(2.0 * M_PI * t / tp_s)));
  }
  hann.t_s.push_back(hold_s);
  hann.value.push_back(0.0);
  return hann;
}

}  // namespace crashlink::testing
