// The run's conditions from a parsed deck: constraints, initial velocities, contacts, rigid walls,
// prescribed motions and loads, probes, controls.
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "solver/contact/segments.h"
#include "solver/deck/model_builder.h"
#include "solver/materials/bilinear_hardening.h"

namespace crashlink::deck::detail {

void Builder::constraints() {
  for (const auto& s : d_.spcs) {
    const Layout l = s.set ? Layout(L::kSpcSet) : Layout(L::kSpcNode);
    std::vector<std::int64_t> one{s.target};
    const auto& ids = s.set ? node_set(s.target, s.ref, s.keyword, l) : one;
    for (auto id : ids) {
      const int i = node(id, s.ref, s.keyword.c_str(), l, 0);
      if (i >= 0) m_.fixed[static_cast<std::size_t>(i)] |= s.mask;
    }
  }
}

void Builder::velocities() {
  for (const auto& v : d_.velocities) {
    const bool generation = v.styp != 0;
    const bool plain = v.styp == 4;  // *INITIAL_VELOCITY
    const Layout l = plain        ? Layout(L::kInitialVelocity1)
                     : generation ? Layout(L::kVelocityGeneration1)
                                  : Layout(L::kVelocityNode);
    const Mat3 r = frame(v.icid, v.ref, v.keyword, l, plain ? 4 : 7);
    const Vec3 vel = mul(r, Vec3{v.v[0] * u_.velocity_m_s(), v.v[1] * u_.velocity_m_s(),
                                 v.v[2] * u_.velocity_m_s()});
    std::vector<std::int64_t> part_ids;
    std::vector<std::int64_t> node_ids;
    if (v.styp == 0) {
      node_ids.push_back(v.target);
    } else if (v.styp == 1) {
      const auto it = part_set_members_.find(v.target);
      if (it == part_set_members_.end())
        fail_at(d_, v.ref, v.keyword, l, 0,
                fmt::format("part set {} is not defined (STYP 1); fix: add *SET_PART_LIST {}",
                            v.target, v.target));
      part_ids = it->second;
    } else if (v.styp == 2) {
      if (!parts_.count(v.target))
        fail_at(d_, v.ref, v.keyword, l, 0,
                fmt::format("part {} is not defined (STYP 2); fix: correct the id", v.target));
      part_ids.push_back(v.target);
    } else if (plain && v.target == 0) {
      node_ids = m_.nodes.id;  // NSID 0: every node (a rigid body's follow its body)
    } else {
      node_ids = node_set(v.target, v.ref, v.keyword, l);
    }
    model::InitialVelocity iv;
    iv.velocity_m_s = vel;
    if (v.omega != 0.0) {  // a spin about the axis through card 2's point
      if (v.axis[0] == -999.0)
        fail_at(d_, v.ref2, v.keyword, L::kVelocityGeneration2, 3,
                "an axis by two nodes (NX = -999, NY and NZ node ids) is not read; fix: write "
                "the axis point XC YC ZC and its direction NX NY NZ");
      const Vec3 n{v.axis[0], v.axis[1], v.axis[2]};
      if (!(norm(n) > 0.0))
        fail_at(d_, v.ref2, v.keyword, L::kVelocityGeneration2, 3,
                "the spin's axis (NX, NY, NZ) is the zero vector; fix: give its direction");
      iv.angular_velocity_rad_s = (v.omega / u_.time_s / norm(n)) * n;
      for (std::size_t k = 0; k < 3; ++k) iv.centre_m[k] = v.centre[k] * u_.length_m;
    }
    // a body's velocity: that of the spin's axis point, the body turning with it
    const auto set_body = [&](model::RigidBody& body) {
      body.velocity_m_s = vel;
      body.velocity_at_point = false;
      body.angular_velocity_rad_s = Vec3{};  // the card's motion replaces the body's
      if (v.omega == 0.0) return;
      body.angular_velocity_rad_s = iv.angular_velocity_rad_s;
      body.velocity_at_point = true;
      body.velocity_point_m = iv.centre_m;
    };
    for (auto pid : part_ids) {
      if (const auto rb = rigid_body_of_part_.find(pid); rb != rigid_body_of_part_.end()) {
        // LS-DYNA's IRIGID 0 (default) keeps a *PART_INERTIA body's velocity; 1 overrides it
        if (inertia_bodies_.count(rb->second) == 0 || v.irigid == 1)
          set_body(m_.rigid_bodies[static_cast<std::size_t>(rb->second)]);
        else
          d_notes_.push_back(
              fmt::format("{}: {}: part {} keeps the velocity of its *PART_INERTIA (IRIGID 0; 1 "
                          "overrides it)",
                          at(d_, v.ref), v.keyword, pid));
        continue;
      }
      const auto p = part_index_.find(pid);
      if (p == part_index_.end()) continue;  // a part without elements
      for (auto i : m_.parts[static_cast<std::size_t>(p->second)].connectivity)
        iv.nodes.push_back(i);
    }
    for (auto id : node_ids) {
      const int i = node(id, v.ref, v.keyword.c_str(), l, 0);
      if (i >= 0) iv.nodes.push_back(i);
    }
    std::sort(iv.nodes.begin(), iv.nodes.end());
    iv.nodes.erase(std::unique(iv.nodes.begin(), iv.nodes.end()), iv.nodes.end());
    {
      // A rigid body with nodes in the set takes the velocity (LS-DYNA: IRIGID 0 protects
      // only *PART_INERTIA velocities); its nodes follow the body, so they leave the list.
      // *INITIAL_VELOCITY: any body; the other cards: the bodies of extra nodes (a nodal rigid
      // body in a part set moving), the rigid parts' bodies being set by part above.
      std::vector<int> body_of(m_.nodes.count(), -1);
      for (std::size_t b = 0; b < m_.rigid_bodies.size(); ++b) {
        if (plain)
          for (int p : m_.rigid_bodies[b].parts)
            for (auto c : m_.parts[static_cast<std::size_t>(p)].connectivity)
              body_of[static_cast<std::size_t>(c)] = static_cast<int>(b);
        for (auto c : m_.rigid_bodies[b].nodes)
          body_of[static_cast<std::size_t>(c)] = static_cast<int>(b);
      }
      std::vector<char> moved(m_.rigid_bodies.size(), 0);
      for (auto c : iv.nodes) {
        const int b = body_of[static_cast<std::size_t>(c)];
        if (b < 0 || moved[static_cast<std::size_t>(b)]) continue;
        moved[static_cast<std::size_t>(b)] = 1;
        if (inertia_bodies_.count(b) == 0 || (generation && v.irigid == 1))
          set_body(m_.rigid_bodies[static_cast<std::size_t>(b)]);
        else
          d_notes_.push_back(fmt::format(
              "{}: {}: rigid body '{}' keeps the velocity of its *PART_INERTIA (_INERTIA)",
              at(d_, v.ref), v.keyword, m_.rigid_bodies[static_cast<std::size_t>(b)].name));
      }
      std::erase_if(iv.nodes,
                    [&](std::int32_t c) { return body_of[static_cast<std::size_t>(c)] >= 0; });
    }
    if (iv.nodes.empty()) continue;
    // Consecutive *INITIAL_VELOCITY_NODE cards with one velocity make one entry.
    if (!generation && !m_.initial_velocities.empty() && last_was_node_ &&
        m_.initial_velocities.back().velocity_m_s == vel &&
        m_.initial_velocities.back().angular_velocity_rad_s == Vec3{}) {
      auto& back = m_.initial_velocities.back().nodes;
      back.insert(back.end(), iv.nodes.begin(), iv.nodes.end());
    } else {
      m_.initial_velocities.push_back(std::move(iv));
    }
    last_was_node_ = !generation;
  }
}

void Builder::rigid_constraints() {
  for (const auto& r : d_.rigid_constraints)
    if (r.kind == RigidConstraintCard::Kind::SpotWeld) max_weld_id_ = std::max(max_weld_id_, r.pid);
  std::vector<char> merged(m_.rigid_bodies.size(), 0);
  std::unordered_map<std::int64_t, int> nodal_ids;  // *CONSTRAINED_NODAL_RIGID_BODY PID -> body
  const auto body_of_part = [&](const RigidConstraintCard& r, std::int64_t pid, Layout l,
                                std::size_t f) {
    const auto it = rigid_body_of_part_.find(pid);
    if (it == rigid_body_of_part_.end())
      fail_at(d_, r.ref, r.keyword, l, f,
              parts_.count(pid)
                  ? fmt::format("part {} is not rigid (*MAT_RIGID); fix: name a rigid part", pid)
                  : fmt::format("part {} is not defined; fix: correct the id", pid));
    return it->second;
  };
  const auto add_nodes = [&](const RigidConstraintCard& r, std::vector<std::int64_t> ids, Layout l,
                             std::size_t f, model::RigidBody& rb) {
    for (auto id : ids) {
      const int c = node(id, r.ref, r.keyword.c_str(), l, f);
      if (c < 0)
        fail_at(d_, r.ref, r.keyword, l, f,
                fmt::format("node {} belongs to no element (it would have no mass); fix: leave "
                            "it out",
                            id));
      if (std::find(rb.nodes.begin(), rb.nodes.end(), c) == rb.nodes.end()) rb.nodes.push_back(c);
    }
  };
  for (const auto& r : d_.rigid_constraints) {
    using K = RigidConstraintCard::Kind;
    if (r.kind == K::NodalBody) {
      const Layout l = L::kNodalRigidBody;
      if (parts_.count(r.pid))
        fail_at(d_, r.ref, r.keyword, l, 0,
                fmt::format("{} is a *PART's id; a nodal rigid body takes an id of its own; fix: "
                            "renumber it",
                            r.pid));
      if (!nodal_ids.emplace(r.pid, 0).second)
        fail_at(d_, r.ref, r.keyword, l, 0,
                fmt::format("nodal rigid body {} is already defined; fix: give each its own id",
                            r.pid));
      model::RigidBody rb;
      rb.name = r.title.empty() ? fmt::format("nodal_rigid_body_{}", r.pid) : r.title;
      for (const auto& other : m_.rigid_bodies)
        if (other.name == rb.name) rb.name += fmt::format(" (PID {})", r.pid);
      add_nodes(r, node_set(r.target, r.ref, r.keyword, l, 2), l, 2, rb);
      rb.fixed = r.fixed;   // _SPC
      if (r.has_inertia) {  // _INERTIA: as *PART_INERTIA's cards
        if (!(r.inertia.mass > 0.0))
          fail_at(d_, r.ref, r.keyword, l, 0,
                  "its _INERTIA cards (XC YC ZC TM, the tensor, the velocities) are missing; "
                  "fix: add them after card 1");
        part_inertia(r.inertia, rb);
        inertia_bodies_.insert(static_cast<int>(m_.rigid_bodies.size()));
      }
      m_.rigid_bodies.push_back(std::move(rb));
      merged.push_back(0);
    } else if (r.kind == K::SpotWeld) {
      const Layout l = r.set ? Layout(L::kGeneralizedWeld1) : Layout(L::kSpotWeld);
      model::RigidBody w;
      if (r.pid > 0 && !weld_ids_.insert(r.pid).second)
        fail_at(
            d_, r.ref, r.keyword, l, 0,
            fmt::format("spot weld {} is already defined; fix: give each weld its own WID", r.pid));
      // an unnumbered weld: the next id above every WID of the deck (names stay unique)
      w.name = r.pid > 0 ? fmt::format("spotweld_{}", r.pid)
                         : fmt::format("spotweld_{}", max_weld_id_ + ++spot_welds_);
      if (r.set) {  // *CONSTRAINED_GENERALIZED_WELD_SPOT: the set's two nodes
        const auto& ids = node_set(r.target, r.ref, r.keyword, l, 0);
        if (ids.size() != 2)
          fail_at(d_, r.ref, r.keyword, l, 0,
                  fmt::format("node set {} holds {} nodes: crashlink's weld failure is that of "
                              "a weld of two nodes (its normal from the first to the second); "
                              "fix: one weld per pair of nodes",
                              r.target, ids.size()));
        add_nodes(r, {ids[0]}, l, 0, w);
        add_nodes(r, {ids[1]}, l, 0, w);
      } else {
        add_nodes(r, {r.target}, l, 0, w);
        add_nodes(r, {r.n2}, l, 1, w);
      }
      if (w.nodes.size() != 2)  // a set naming one node twice
        fail_at(d_, r.ref, r.keyword, l, 0,
                "the weld's two nodes are one node; fix: weld two distinct nodes");
      const auto a = static_cast<std::size_t>(w.nodes[0]), b = static_cast<std::size_t>(w.nodes[1]);
      double gap = 0.0;
      for (std::size_t d = 0; d < 3; ++d)
        gap += (m_.nodes.x0[3 * a + d] - m_.nodes.x0[3 * b + d]) *
               (m_.nodes.x0[3 * a + d] - m_.nodes.x0[3 * b + d]);
      if (!(gap > 0.0))
        fail_at(d_, r.ref, r.keyword, l, r.set ? 0 : 1,
                "lies where N1 lies: a weld's normal runs from N1 to N2; fix: weld nodes of the "
                "two sheets, apart by their gap");
      w.failure.normal_N = r.sn * u_.force_N();
      w.failure.shear_N = r.ss * u_.force_N();
      w.failure.exp_n = r.exp_n > 0.0 ? r.exp_n : 2.0;
      w.failure.exp_m = r.exp_m > 0.0 ? r.exp_m : 2.0;
      w.failure.time_s = r.tf * u_.time_s;
      m_.rigid_bodies.push_back(std::move(w));
      merged.push_back(0);
    } else if (r.kind == K::ExtraNodes) {
      const Layout l = L::kExtraNodes;
      const int b = body_of_part(r, r.pid, l, 0);
      add_nodes(r, r.set ? node_set(r.target, r.ref, r.keyword, l, 1) : std::vector{r.target}, l, 1,
                m_.rigid_bodies[static_cast<std::size_t>(b)]);
    } else {
      const Layout l = L::kRigidBodies;
      const int lead = body_of_part(r, r.pid, l, 0), other = body_of_part(r, r.target, l, 1);
      if (lead == other) continue;  // already one body
      auto& to = m_.rigid_bodies[static_cast<std::size_t>(lead)];
      auto& from = m_.rigid_bodies[static_cast<std::size_t>(other)];
      if (inertia_bodies_.count(other))
        d_notes_.push_back(
            fmt::format("{}: {}: part {}'s *PART_INERTIA is left out: the body of "
                        "lead part {} is the merged body's (LS-DYNA)",
                        at(d_, r.ref), r.keyword, r.target, r.pid));
      if (from.fixed != 0 && from.fixed != to.fixed)
        d_notes_.push_back(
            fmt::format("{}: {}: part {}'s *MAT_RIGID constraints are left out: the lead part "
                        "{}'s hold the merged body (LS-DYNA)",
                        at(d_, r.ref), r.keyword, r.target, r.pid));
      to.parts.insert(to.parts.end(), from.parts.begin(), from.parts.end());
      for (auto c : from.nodes)
        if (std::find(to.nodes.begin(), to.nodes.end(), c) == to.nodes.end()) to.nodes.push_back(c);
      from.parts.clear();
      from.nodes.clear();
      merged[static_cast<std::size_t>(other)] = 1;
      for (auto& [pid, b] : rigid_body_of_part_)
        if (b == other) b = lead;
    }
  }
  // Drop the merged bodies, renumbering the maps that hold body indices.
  std::vector<int> index(m_.rigid_bodies.size(), -1);
  std::vector<model::RigidBody> kept;
  for (std::size_t b = 0; b < m_.rigid_bodies.size(); ++b) {
    if (merged[b]) continue;
    index[b] = static_cast<int>(kept.size());
    kept.push_back(std::move(m_.rigid_bodies[b]));
  }
  m_.rigid_bodies = std::move(kept);
  for (auto& [pid, b] : rigid_body_of_part_) b = index[static_cast<std::size_t>(b)];
  std::unordered_set<int> inertia;
  for (int b : inertia_bodies_)
    if (index[static_cast<std::size_t>(b)] >= 0) inertia.insert(index[static_cast<std::size_t>(b)]);
  inertia_bodies_ = std::move(inertia);
}

std::vector<int> Builder::surface_parts(const ContactCard& k, bool slave) {
  const std::int64_t id = slave ? k.ssid : k.msid;
  const int typ = slave ? k.sstyp : k.mstyp;
  const std::size_t id_field = slave ? 0 : 1, typ_field = slave ? 2 : 3;
  std::vector<int> out;
  const bool all = typ == 5 || (id == 0 && k.kind == ContactCard::Kind::SingleSurface);
  if (all) {
    for (std::size_t p = 0; p < m_.parts.size(); ++p) out.push_back(static_cast<int>(p));
    return out;
  }
  if (id == 0)
    fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
            fmt::format("the {} surface is not given; fix: write a part (TYP 3) or part set "
                        "(TYP 2) id",
                        slave ? "slave" : "master"));
  std::vector<std::int64_t> pids;
  if (typ == 3) {
    if (!parts_.count(id))
      fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
              fmt::format("part {} is not defined; fix: correct the id", id));
    pids.push_back(id);
  } else if (typ == 2) {
    const auto it = part_set_members_.find(id);
    if (it == part_set_members_.end())
      fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
              fmt::format("part set {} is not defined; fix: add *SET_PART_LIST {}", id, id));
    pids = it->second;
  } else {
    fail_at(d_, k.ref, k.keyword, L::kContact1, typ_field,
            fmt::format("surface type {} is not read: crashlink takes a contact surface as "
                        "parts (3), a part set (2){}{}; fix: name the parts",
                        typ,
                        slave && k.kind != ContactCard::Kind::SingleSurface
                            ? ", a segment set (0, slave only), a shell set (1, slave only), "
                              "a node set (4, slave only)"
                            : "",
                        " or all parts (5)"));
  }
  for (auto pid : pids)
    if (const auto p = part_index_.find(pid); p != part_index_.end()) out.push_back(p->second);
  if (out.empty())
    fail_at(d_, k.ref, k.keyword, L::kContact1, id_field,
            fmt::format("the {} surface holds no element; fix: name parts with elements",
                        slave ? "slave" : "master"));
  return out;
}

std::vector<std::int32_t> Builder::segment_faces(const ContactCard& k) {
  const auto it = std::find_if(d_.segment_sets.begin(), d_.segment_sets.end(),
                               [&](const SegmentSetCard& s) { return s.id == k.ssid; });
  if (k.ssid == 0 || it == d_.segment_sets.end())
    fail_at(d_, k.ref, k.keyword, L::kContact1, 0,
            fmt::format("segment set {} is not defined (SSTYP 0: a segment set); fix: add "
                        "*SET_SEGMENT {}, or name parts (SSTYP 3) or a part set (SSTYP 2)",
                        k.ssid, k.ssid));
  const SegmentSetCard& s = *it;
  if (element_faces_.empty()) {  // every element's faces, corners sorted, as keys
    for (const auto& p : m_.parts) {
      const auto& q = p.connectivity;
      if (p.kind == model::ElementKind::Shell4) {
        for (std::size_t e = 0; 4 * e < q.size(); ++e)
          element_faces_.insert(face_key(q[4 * e], q[4 * e + 1], q[4 * e + 2], q[4 * e + 3]));
      } else {
        for (std::size_t e = 0; 8 * e < q.size(); ++e)
          for (const auto& f : contact::kHexFaces)
            element_faces_.insert(face_key(q[8 * e + static_cast<std::size_t>(f[0])],
                                           q[8 * e + static_cast<std::size_t>(f[1])],
                                           q[8 * e + static_cast<std::size_t>(f[2])],
                                           q[8 * e + static_cast<std::size_t>(f[3])]));
      }
    }
  }
  std::vector<std::int32_t> faces;
  faces.reserve(s.nodes.size());
  for (std::size_t f = 0; f < s.segment_ref.size(); ++f) {
    std::int32_t n[4];
    for (std::size_t j = 0; j < 4; ++j) {
      n[j] = node(s.nodes[4 * f + j], s.segment_ref[f], s.keyword.c_str(), L::kSetSegment, j);
      if (n[j] < 0)
        fail_at(d_, s.segment_ref[f], s.keyword, L::kSetSegment, j,
                fmt::format("node {} belongs to no element; fix: give the faces of elements",
                            s.nodes[4 * f + j]));
    }
    if (!element_faces_.count(face_key(n[0], n[1], n[2], n[3])))
      fail_at(d_, s.segment_ref[f], s.keyword, L::kSetSegment, 0,
              "is not a face of an element (a shell, or a side of a hexahedron); fix: give "
              "the corners of an element's face");
    faces.insert(faces.end(), n, n + 4);
  }
  if (faces.empty())
    fail_at(d_, s.ref, s.keyword, L::kSetHeader, 0,
            "holds no segment; fix: list the faces (N1 N2 N3 N4 per card)");
  return faces;
}

std::array<std::int32_t, 4> Builder::face_key(std::int32_t a, std::int32_t b, std::int32_t c,
                                              std::int32_t d) {
  std::array<std::int32_t, 4> k{a, b, c, d};
  std::sort(k.begin(), k.end());
  return k;
}

std::string Builder::contact_name(const ContactCard& k, std::size_t i) {
  const std::string tag = k.cid > 0 ? std::to_string(k.cid) : std::to_string(i + 1);
  std::string name = k.heading.empty() ? "contact_" + tag : k.heading;
  if (used_contact_names_.count(name)) name += k.cid > 0 ? " (CID " + tag + ")" : " (" + tag + ")";
  for (int extra = 2; used_contact_names_.count(name); ++extra)
    name = fmt::format("{} #{}", name, extra);
  used_contact_names_.emplace(name, 0);
  return name;
}

void Builder::contacts() {
  for (std::size_t i = 0; i < d_.contacts.size(); ++i) {
    const ContactCard& k = d_.contacts[i];
    model::Contact c;
    c.name = contact_name(k, i);
    c.kind = k.kind == ContactCard::Kind::SingleSurface    ? model::ContactKind::SingleSurface
             : k.kind == ContactCard::Kind::NodesToSurface ? model::ContactKind::NodeToSurface
                                                           : model::ContactKind::SurfaceToSurface;
    if (k.kind == ContactCard::Kind::SingleSurface) {
      c.master_parts = surface_parts(k, true);
    } else {
      if (k.sstyp == 0) {
        // *SET_SEGMENT: the faces as given; their nodes are the slave nodes.
        const auto faces = segment_faces(k);
        c.slave_nodes.assign(faces.begin(), faces.end());
        if (k.kind == ContactCard::Kind::SurfaceToSurface) c.slave_faces = faces;
      } else if (k.sstyp == 1) {
        // *SET_SHELL_LIST: the shells' faces (a triangle repeats its third corner)
        const auto it = shell_set_members_.find(k.ssid);
        if (it == shell_set_members_.end())
          fail_at(d_, k.ref, k.keyword, L::kContact1, 0,
                  fmt::format("shell set {} is not defined (SSTYP 1: a shell set); fix: add "
                              "*SET_SHELL_LIST {}",
                              k.ssid, k.ssid));
        std::vector<std::int32_t> faces;
        for (auto eid : it->second) {
          const auto [p, e] = shell_at_.at(eid);
          const auto& q = m_.parts[static_cast<std::size_t>(p)].connectivity;
          faces.insert(faces.end(), q.begin() + 4 * e, q.begin() + 4 * e + 4);
        }
        c.slave_nodes.assign(faces.begin(), faces.end());
        if (k.kind == ContactCard::Kind::SurfaceToSurface) c.slave_faces = faces;
      } else if (k.sstyp == 4) {
        for (auto id : node_set(k.ssid, k.ref, k.keyword, L::kContact1)) {
          const int n = node(id, k.ref, k.keyword.c_str(), L::kContact1, 0);
          if (n >= 0) c.slave_nodes.push_back(n);
        }
      } else {
        for (int p : surface_parts(k, true))
          for (auto n : m_.parts[static_cast<std::size_t>(p)].connectivity)
            c.slave_nodes.push_back(n);
      }
      std::sort(c.slave_nodes.begin(), c.slave_nodes.end());
      c.slave_nodes.erase(std::unique(c.slave_nodes.begin(), c.slave_nodes.end()),
                          c.slave_nodes.end());
      if (c.slave_nodes.empty())
        fail_at(d_, k.ref, k.keyword, L::kContact1, 0,
                "the slave surface holds no node of an element; fix: correct the set");
      c.master_parts = surface_parts(k, false);
    }
    if (k.sfs != k.sfm && k.kind != ContactCard::Kind::SingleSurface)
      fail_at(d_, k.ref3, k.keyword, L::kContact3, 1,
              fmt::format("crashlink has one penalty scale per contact and SFS = {}; fix: "
                          "write SFM = SFS",
                          k.sfs));
    c.penalty_scale = d_.slsfac * k.sfs;  // *CONTROL_CONTACT SLSFAC (default 0.1)
    c.slave_thickness_m = k.sst * u_.length_m;
    c.master_thickness_m = k.mst * u_.length_m;
    {
      // SST/MST set the shells' thickness offsets; solid faces keep theirs (0): said so
      const auto has_solids = [&](const std::vector<int>& parts) {
        for (int p : parts)
          if (m_.parts[static_cast<std::size_t>(p)].kind == model::ElementKind::Hex8) return true;
        return false;
      };
      std::vector<int> slave_parts;
      if (c.kind != model::ContactKind::SingleSurface) {
        std::vector<char> on(m_.nodes.count(), 0);
        for (auto n : c.slave_nodes) on[static_cast<std::size_t>(n)] = 1;
        for (std::size_t p = 0; p < m_.parts.size(); ++p)
          for (auto n : m_.parts[p].connectivity)
            if (on[static_cast<std::size_t>(n)]) {
              slave_parts.push_back(static_cast<int>(p));
              break;
            }
      }
      const bool self = c.kind == model::ContactKind::SingleSurface;
      if ((k.sst > 0.0 && has_solids(self ? c.master_parts : slave_parts)) ||
          (k.mst > 0.0 && !self && has_solids(c.master_parts)))
        d_notes_.push_back(fmt::format(
            "{}: {}: SST/MST set the contact thickness of the side's shells; its solid faces "
            "keep their offset 0",
            at(d_, k.ref3), k.keyword));
      if (self && k.mst > 0.0)
        d_notes_.push_back(
            fmt::format("{}: {}: a single surface has one side: MST without "
                        "effect (SST is its thickness)",
                        at(d_, k.ref3), k.keyword));
    }
    c.soft = k.soft == 1;
    c.soft_scale = k.sofscl;
    c.static_friction = k.fs;
    c.dynamic_friction = k.fd == 0.0 && k.dc == 0.0 ? k.fs : k.fd;
    c.friction_decay_s_m = k.dc * u_.time_s / u_.length_m;
    if (!k.automatic)
      d_notes_.push_back(fmt::format(
          "{}: {}: computed as its automatic form (crashlink's contact finds either side of "
          "a shell, whatever its normal)",
          at(d_, k.ref), k.keyword));
    m_.contacts.push_back(std::move(c));
  }
}

void Builder::rigid_walls() {
  std::vector<char> on_body(m_.nodes.count(), 0);
  for (const auto& rb : m_.rigid_bodies) {
    for (int p : rb.parts)
      for (auto c : m_.parts[static_cast<std::size_t>(p)].connectivity)
        on_body[static_cast<std::size_t>(c)] = 1;
    for (auto c : rb.nodes) on_body[static_cast<std::size_t>(c)] = 1;  // welds, nodal bodies
  }
  for (std::size_t i = 0; i < d_.rigid_walls.size(); ++i) {
    const RigidWallCard& k = d_.rigid_walls[i];
    model::RigidWall w;
    w.name = k.heading.empty() ? fmt::format("rigidwall_{}", i + 1) : k.heading;
    if (!used_wall_names_.insert(w.name).second) {  // a heading met twice: made unique
      const std::string base = w.name;
      w.name = fmt::format("{} ({})", base, i + 1);
      for (int extra = 2; !used_wall_names_.insert(w.name).second; ++extra)
        w.name = fmt::format("{} ({}) #{}", base, i + 1, extra);
    }
    Vec3 n{};
    for (std::size_t c = 0; c < 3; ++c) {
      w.point_m[c] = k.tail[c] * u_.length_m;
      n[c] = k.head[c] - k.tail[c];
    }
    const double len = norm(n);
    if (!(len > 0.0))
      fail_at(d_, k.ref2, k.keyword, L::kRigidWall2, 3,
              "the head point is the tail point: the wall has no normal; fix: put the head on "
              "the side of the nodes the wall stops");
    w.normal = (1.0 / len) * n;
    if (k.kind == RigidWallCard::Kind::Cylinder) {  // the axis from tail to head
      w.shape = model::RigidWall::Shape::Cylinder;
      w.radius_m = k.radius * u_.length_m;
      w.length_m = k.length * u_.length_m;
    } else if (k.finite && k.len_l > 0.0) {
      // the edge l from the tail to (XHEV, YHEV, ZHEV), in the plane; m = n x l
      Vec3 l{};
      for (std::size_t c = 0; c < 3; ++c) l[c] = k.edge_head[c] - k.tail[c];
      const double ll = norm(l);
      // (within 1e-3: an oblique wall written with 5 digits in 10 columns; projected below)
      if (!(ll > 0.0) || std::abs(dot(l, w.normal)) > 1e-3 * ll)
        fail_at(d_, k.ref_shape, k.keyword, L::kRigidWallFinite, 0,
                fmt::format("the edge l from the tail ({}, {}, {}) to (XHEV, YHEV, ZHEV) must be "
                            "a vector in the wall's plane (l.n = {:.4g} of |l| = {:.4g}); fix: "
                            "put the edge's head in the plane, off the tail",
                            k.tail[0], k.tail[1], k.tail[2], ll > 0.0 ? dot(l, w.normal) / ll : 0.0,
                            ll));
      l = l - dot(l, w.normal) * w.normal;  // the round-off out of the plane
      w.edge = (1.0 / norm(l)) * l;
      w.length_m = k.len_l * u_.length_m;
      w.width_m = k.len_m * u_.length_m;
    }
    if (k.moving) {  // *RIGIDWALL_PLANAR_MOVING: MASS, V0 along the normal (toward the nodes)
      w.mass_kg = k.mass * u_.mass_kg;
      w.velocity_m_s = k.v0 * u_.velocity_m_s();
    }
    if (k.nsid == 0) {
      for (std::size_t c = 0; c < m_.nodes.count(); ++c)
        w.nodes.push_back(static_cast<std::int32_t>(c));
    } else {
      for (auto id : node_set(k.nsid, k.ref, k.keyword, L::kRigidWall1)) {
        const int c = node(id, k.ref, k.keyword.c_str(), L::kRigidWall1, 0);
        if (c >= 0) w.nodes.push_back(c);
      }
      std::sort(w.nodes.begin(), w.nodes.end());
      w.nodes.erase(std::unique(w.nodes.begin(), w.nodes.end()), w.nodes.end());
    }
    // A rigid body's nodes follow the body: the wall leaves them out, and says so.
    const auto rigid = std::erase_if(
        w.nodes, [&](std::int32_t c) { return on_body[static_cast<std::size_t>(c)] != 0; });
    if (rigid > 0)
      d_notes_.push_back(fmt::format("{}: {}: {} nodes of rigid bodies left out of the wall",
                                     at(d_, k.ref), k.keyword, rigid));
    if (w.nodes.empty())
      fail_at(d_, k.ref, k.keyword, L::kRigidWall1, 0,
              "the wall stops no node of a deformable element; fix: correct NSID");
    m_.rigid_walls.push_back(std::move(w));
  }
}

model::Curve Builder::time_curve(std::int64_t lcid, double sf, double unit, const CardRef& ref,
                                 const std::string& keyword, Layout l, std::size_t field) {
  const auto it = curves_.find(lcid);
  if (it == curves_.end())
    fail_at(d_, ref, keyword, l, field,
            fmt::format("curve {} is not defined; fix: add *DEFINE_CURVE {}", lcid, lcid));
  const CurveCard& cv = d_.curves[static_cast<std::size_t>(it->second)];
  model::Curve c;
  for (std::size_t i = 0; i < cv.a.size(); ++i) {
    c.t_s.push_back(cv.sfa * (cv.a[i] + cv.offa) * u_.time_s);
    c.value.push_back(sf * cv.sfo * (cv.o[i] + cv.offo) * unit);
  }
  return c;
}

void Builder::curve_dofs() {
  int motions = 0, loads = 0;
  for (const CurveDofCard& k : d_.curve_dofs) {
    const Layout l = k.load    ? (k.set ? Layout(L::kLoadSet) : Layout(L::kLoadNode))
                     : k.rigid ? Layout(L::kMotionRigid)
                               : (k.set ? Layout(L::kMotionSet) : Layout(L::kMotionNode));
    const bool rotation = k.dof >= 5;
    const int dof = rotation ? k.dof - 2 : k.dof - 1;  // model: 0-2 x, y, z; 3-5 rotations
    const auto motion_curve = [&] {
      const double unit = k.vad == 2 ? (rotation ? 1.0 : u_.length_m)
                                     : (rotation ? 1.0 / u_.time_s : u_.velocity_m_s());
      model::Curve c = time_curve(k.lcid, k.sf, unit, k.ref, k.keyword, l, 3);
      if (k.vad == 2) c = displacement_to_velocity(c, k);
      return c;
    };
    if (k.rigid) {  // a rigid part's body
      const auto it = rigid_body_of_part_.find(k.target);
      if (it == rigid_body_of_part_.end())
        fail_at(d_, k.ref, k.keyword, l, 0,
                fmt::format("part {} is not a rigid part (*MAT_RIGID) with elements; fix: name a "
                            "rigid part, or drive a deformable part's nodes with "
                            "*BOUNDARY_PRESCRIBED_MOTION_SET",
                            k.target));
      const auto& body = m_.rigid_bodies[static_cast<std::size_t>(it->second)];
      if (body.fixed & (1u << dof))
        fail_at(d_, k.ref, k.keyword, l, 1,
                fmt::format("rigid body '{}' (part {}) already holds this dof (*MAT_RIGID "
                            "CON1/CON2 or a nodal body's _SPC); fix: free it there or drive "
                            "another dof",
                            body.name, k.target));
      model::PrescribedVelocity pv;
      pv.name = fmt::format("motion_{}", ++motions);
      pv.rigid_body = it->second;
      pv.dof = dof;
      pv.velocity = motion_curve();
      m_.prescribed_velocities.push_back(std::move(pv));
      continue;
    }
    std::vector<std::int64_t> one{k.target};
    const auto& ids = k.set ? node_set(k.target, k.ref, k.keyword, l) : one;
    std::vector<std::int32_t> nodes;
    for (auto id : ids) {
      const int i = node(id, k.ref, k.keyword.c_str(), l, 0);
      if (i < 0 && !k.set)
        fail_at(d_, k.ref, k.keyword, l, 0,
                fmt::format("node {} belongs to no element (crashlink leaves such nodes out); "
                            "fix: drive a node of an element",
                            id));
      if (i >= 0) nodes.push_back(i);
    }
    if (nodes.empty())
      fail_at(d_, k.ref, k.keyword, l, 0,
              "the set holds no node of an element; fix: correct the set");
    const std::size_t lcid_field = k.load ? 2 : 3;
    if (k.load) {
      model::NodalLoad ld;
      ld.name = fmt::format("load_{}", ++loads);
      ld.nodes = std::move(nodes);
      ld.dof = dof;
      ld.force = time_curve(k.lcid, k.sf, u_.force_N(), k.ref, k.keyword, l, lcid_field);
      m_.loads.push_back(std::move(ld));
    } else {
      model::PrescribedVelocity pv;
      pv.name = fmt::format("motion_{}", ++motions);
      pv.nodes = std::move(nodes);
      pv.dof = dof;
      pv.velocity = motion_curve();
      m_.prescribed_velocities.push_back(std::move(pv));
    }
  }
}

/// VAD 2: the displacement curve d(t) (SI) as the velocity that moves the node along it: on
/// each segment its slope (d_{i+1} - d_i) / (t_{i+1} - t_i), held from 1e-6 of the shortest
/// segment after t_i to as much before t_{i+1} (the curve steps between), 0 before the first
/// point and after the last. The displacement integrated from it meets d(t_i) within 1e-6 of
/// the largest step in velocity times the shortest segment. d(0) must be 0: the nodes start
/// where they are.
model::Curve Builder::displacement_to_velocity(const model::Curve& d, const CurveDofCard& k) {
  const Layout l =
      k.rigid ? Layout(L::kMotionRigid) : (k.set ? Layout(L::kMotionSet) : Layout(L::kMotionNode));
  if (d.t_s.size() < 2 || std::abs(d.at(0.0)) > 1e-12 * (1.0 + std::abs(d.value.back())))
    fail_at(d_, k.ref, k.keyword, l, 3,
            fmt::format("a displacement curve (VAD 2) needs 2 points or more and d(0) = 0 (the "
                        "nodes start where they are); curve {} has {} point(s), d(0) = {:.4g} m; "
                        "fix: start it at 0",
                        k.lcid, d.t_s.size(), d.at(0.0)));
  double shortest = d.t_s.back() - d.t_s.front();
  for (std::size_t i = 0; i + 1 < d.t_s.size(); ++i)
    shortest = std::min(shortest, d.t_s[i + 1] - d.t_s[i]);
  const double eps = 1e-6 * shortest;
  model::Curve v;
  v.t_s.push_back(d.t_s.front());
  v.value.push_back(0.0);
  for (std::size_t i = 0; i + 1 < d.t_s.size(); ++i) {
    const double slope = (d.value[i + 1] - d.value[i]) / (d.t_s[i + 1] - d.t_s[i]);
    v.t_s.push_back(d.t_s[i] + eps);
    v.value.push_back(slope);
    v.t_s.push_back(d.t_s[i + 1] - eps);
    v.value.push_back(slope);
  }
  v.t_s.push_back(d.t_s.back());
  v.value.push_back(0.0);
  return v;
}

void Builder::probes() {
  std::unordered_set<std::string> seen;  // node id and heading: a node named twice alike once
  std::unordered_set<std::string> names;
  // *DATABASE_RBDOUT: every rigid body's motion (LS-DYNA's rbdout), named after the body.
  if (d_.rigid_body_output)
    for (std::size_t b = 0; b < m_.rigid_bodies.size(); ++b) {
      model::Probe p;
      p.name = m_.rigid_bodies[b].name;
      std::replace(p.name.begin(), p.name.end(), '/', '_');
      names.insert(p.name);
      p.kind = model::Probe::Kind::RigidBody;
      p.index = static_cast<int>(b);
      m_.probes.push_back(std::move(p));
    }
  for (const HistoryNodeCard& h : d_.history_nodes) {
    const bool with_id = h.keyword.ends_with("_ID");
    const Layout l = with_id ? Layout(L::kIdHeading) : Layout(L::kHistoryIds);
    std::vector<std::int64_t> one{h.id};
    const auto& ids = h.set ? node_set(h.id, h.ref, h.keyword, l, h.field) : one;
    for (const auto id : ids) {
      const int c = node(id, h.ref, h.keyword.c_str(), l, h.field);
      if (c < 0 && h.set) continue;  // a set's node in no element: left out, as everywhere
      if (c < 0)
        fail_at(d_, h.ref, h.keyword, l, h.field,
                fmt::format("node {} belongs to no element (crashlink leaves such nodes out); "
                            "fix: probe a node of an element",
                            id));
      if (!seen.insert(fmt::format("{}|{}", id, h.heading)).second) continue;
      model::Probe p;
      // The heading names the probe (an HDF5 path element: no '/'); a heading met twice gets
      // the node id appended.
      p.name = h.heading.empty() ? fmt::format("node_{}", id) : h.heading;
      std::replace(p.name.begin(), p.name.end(), '/', '_');
      if (!names.insert(p.name).second) {
        const std::string base = p.name;
        p.name = fmt::format("{}_{}", base, id);
        for (int k = 2; !names.insert(p.name).second; ++k)
          p.name = fmt::format("{}_{}_{}", base, id, k);
      }
      p.kind = model::Probe::Kind::Node;
      p.index = c;
      m_.probes.push_back(std::move(p));
    }
  }
}

void Builder::controls() {
  if (!d_.has_end_time)
    throw InputError(d_.files.name(0), 0, "*CONTROL_TERMINATION",
                     "missing: the deck sets no end time; fix: add *CONTROL_TERMINATION with "
                     "ENDTIM");
  m_.controls.end_time_s = d_.end_time * u_.time_s;
  m_.controls.dt_scale = d_.tssfac;
  m_.controls.mass_scaling_dt_s = std::abs(d_.dt2ms) * u_.time_s;  // applied by read_deck
  // *DATABASE_GLSTAT ... DT: one history interval for every series (the smallest given);
  // *DATABASE_BINARY_D3PLOT DT: the field states' interval.
  m_.controls.history_interval_s = d_.history_dt * u_.time_s;
  m_.controls.field_interval_s = d_.field_count > 0
                                     ? m_.controls.end_time_s / static_cast<double>(d_.field_count)
                                     : d_.field_dt * u_.time_s;
  if (d_.has_bulk) {
    m_.controls.bulk_q_quadratic = d_.bulk_q1;
    m_.controls.bulk_q_linear = d_.bulk_q2;
    m_.controls.shell_bulk_viscosity = d_.bulk_shells;
  }
  // *LOAD_BODY_*: a base acceleration a (LS-DYNA): the body load is -rho a, so gravity along
  // -z is *LOAD_BODY_Z with +9.81 m/s^2. Constant curves only.
  for (const auto& l : d_.body_loads) {
    const auto it = curves_.find(l.curve);
    if (it == curves_.end())
      fail_at(d_, l.ref, l.keyword, L::kLoadBody, 0,
              fmt::format("curve {} is not defined; fix: add *DEFINE_CURVE {}", l.curve, l.curve));
    const CurveCard& cv = d_.curves[static_cast<std::size_t>(it->second)];
    const double a0 = cv.sfo * (cv.o.front() + cv.offo);
    for (double o : cv.o)
      if (std::abs(cv.sfo * (o + cv.offo) - a0) > 1e-12 * std::abs(a0))
        fail_at(d_, l.ref, l.keyword, L::kLoadBody, 0,
                fmt::format("curve {} changes in time ({} at {}:{}): crashlink's body "
                            "acceleration is constant; fix: a curve with one value",
                            l.curve, cv.keyword, d_.files.name(cv.ref.file), cv.ref.line));
    const double a_m_s2 = l.sf * a0 * u_.length_m / (u_.time_s * u_.time_s);
    m_.controls.gravity_m_s2[static_cast<std::size_t>(l.axis)] -= a_m_s2;
  }
}

}  // namespace crashlink::deck::detail
