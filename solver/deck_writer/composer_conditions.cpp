// The run's conditions: constraints, initial velocities, prescribed motions and loads, contacts,
// rigid walls, probes; and the sets and curves they name.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "core/errors.h"
#include "solver/contact/segments.h"
#include "solver/deck_writer/composer.h"

namespace crashlink::deck_writer::detail {

namespace {

/// The model's nodes of part p, ascending.
std::vector<std::int32_t> part_nodes(const model::Part& p) {
  std::vector<std::int32_t> n(p.connectivity.begin(), p.connectivity.end());
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

std::vector<std::int32_t> sorted_unique(std::vector<std::int32_t> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace

std::int64_t Composer::node_set(const std::vector<std::int32_t>& nodes, const std::string& title) {
  const std::int64_t id = next_node_set_++;
  KeywordBlock b("*SET_NODE_LIST_TITLE");
  b.line(title);
  b.card(L::kSetHeader, {static_cast<long long>(id)});
  std::vector<std::int64_t> ids;
  ids.reserve(nodes.size());
  for (auto n : nodes) ids.push_back(node_id(n));
  list_cards(b, ids);
  emit(b);
  return id;
}

std::int64_t Composer::part_set(const std::vector<int>& parts, const std::string& title) {
  const std::int64_t id = next_part_set_++;
  KeywordBlock b("*SET_PART_LIST_TITLE");
  b.line(title);
  b.card(L::kSetHeader, {static_cast<long long>(id)});
  std::vector<std::int64_t> ids;
  for (int p : parts) ids.push_back(part_id_[static_cast<std::size_t>(p)]);
  list_cards(b, ids);
  emit(b);
  return id;
}

std::int64_t Composer::curve(const std::vector<double>& a, const std::vector<double>& o,
                             const std::string& title) {
  const std::int64_t id = next_curve_++;
  KeywordBlock b("*DEFINE_CURVE_TITLE");
  b.line(title);
  b.card(L::kCurve, {static_cast<long long>(id)});
  for (std::size_t k = 0; k < a.size(); ++k) b.card(L::kCurvePoint, {a[k], o[k]});
  emit(b);
  return id;
}

std::int64_t Composer::curve(const model::Curve& c, double value_unit_SI,
                             const std::string& title) {
  std::vector<double> a, o;
  for (std::size_t k = 0; k < c.t_s.size(); ++k) {
    a.push_back(time(c.t_s[k]));
    o.push_back(c.value[k] / value_unit_SI);
  }
  if (a.empty()) a = {0.0}, o = {0.0};
  const double end = time(m_.controls.end_time_s);
  if (a.size() == 1 && end > a[0]) {  // a constant: two points over the run (LS-DYNA's habit)
    a.push_back(end);
    o.push_back(o[0]);
  }
  return curve(a, o, title);
}

void Composer::rigid_constraints() {
  std::int64_t next_pid = 0;  // nodal rigid bodies' ids: above every part's
  for (auto pid : part_id_) next_pid = std::max(next_pid, pid);
  // Spot welds: a deck names one by its WID (the reader: spotweld_<WID>); a weld named so keeps
  // its WID, another gets the next free one (noted).
  std::set<long long> wids;
  const auto wid_of = [](const std::string& name) -> long long {
    const std::string prefix = "spotweld_";
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() ||
        name.size() > prefix.size() + 9)
      return 0;
    long long v = 0;
    for (std::size_t i = prefix.size(); i < name.size(); ++i) {
      if (name[i] < '0' || name[i] > '9') return 0;
      v = 10 * v + (name[i] - '0');
    }
    return v;
  };
  for (const auto& rb : m_.rigid_bodies)
    if (rb.failure.any() && wid_of(rb.name) > 0) wids.insert(wid_of(rb.name));
  long long next_wid = 0;
  for (std::size_t k = 0; k < m_.rigid_bodies.size(); ++k) {
    const auto& rb = m_.rigid_bodies[k];
    if (rb.failure.any()) {
      long long wid = wid_of(rb.name);
      if (wid == 0) {
        while (wids.count(++next_wid)) {
        }
        wid = next_wid;
        wids.insert(wid);
        notes_.push_back(
            fmt::format("spot weld '{}' is *CONSTRAINED_SPOTWELD_ID {} in the deck "
                        "(read back as 'spotweld_{}': a deck names welds by id)",
                        rb.name, wid, wid));
      }
      const auto& f = rb.failure;
      KeywordBlock b("*CONSTRAINED_SPOTWELD_ID");
      b.card(L::kSpotWeldId, {wid});
      b.card(L::kSpotWeld,
             {static_cast<long long>(node_id(rb.nodes[0])),
              static_cast<long long>(node_id(rb.nodes[1])), force(f.normal_N), force(f.shear_N),
              f.exp_n, f.exp_m, f.time_s > 0.0 ? Value(time(f.time_s)) : Value()});
      emit(b);
      continue;
    }
    if (rb.parts.empty()) {
      // its given mass and inertia as _INERTIA (the whole body as the solver builds it, and its
      // velocities), its held dofs as _SPC (check_exportable: not both)
      const bool inertia = nodal_inertia_given(rb);
      const std::int64_t sid = node_set(rb.nodes, rb.name + " nodes");
      KeywordBlock b(inertia         ? "*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_TITLE"
                     : rb.fixed != 0 ? "*CONSTRAINED_NODAL_RIGID_BODY_SPC_TITLE"
                                     : "*CONSTRAINED_NODAL_RIGID_BODY_TITLE");
      b.line(rb.name);
      b.card(L::kNodalRigidBody,
             {static_cast<long long>(++next_pid), 0, static_cast<long long>(sid)});
      if (inertia) {
        const auto& body = body_states_[k];
        const double s = u_.mass_kg * u_.length_m * u_.length_m;
        const auto& J = body.inertia_body;
        b.card(L::kPartInertia3, {length(body.centre0[0]), length(body.centre0[1]),
                                  length(body.centre0[2]), mass(body.mass_kg), 0, 0});
        b.card(L::kPartInertia4,
               {J[0][0] / s, J[0][1] / s, J[0][2] / s, J[1][1] / s, J[1][2] / s, J[2][2] / s});
        // the centre's velocity (the body's own, or from its spin about a point)
        const Vec3 vc = rb.velocity_at_point ? body.velocity : rb.velocity_m_s;
        b.card(L::kPartInertia5,
               {velocity(vc[0]), velocity(vc[1]), velocity(vc[2]),
                rb.angular_velocity_rad_s[0] * u_.time_s, rb.angular_velocity_rad_s[1] * u_.time_s,
                rb.angular_velocity_rad_s[2] * u_.time_s});
      }
      if (rb.fixed != 0)
        b.card(L::kMatRigid2, {1.0, con_code(rb.fixed & 7), con_code((rb.fixed >> 3) & 7)});
      emit(b);
      continue;
    }
    const long long lead = part_id_[static_cast<std::size_t>(rb.parts[0])];
    for (std::size_t j = 1; j < rb.parts.size(); ++j) {
      KeywordBlock b("*CONSTRAINED_RIGID_BODIES");
      b.card(L::kRigidBodies,
             {lead, static_cast<long long>(part_id_[static_cast<std::size_t>(rb.parts[j])])});
      emit(b);
    }
    if (!rb.nodes.empty()) {
      const std::int64_t sid = node_set(rb.nodes, rb.name + " extra nodes");
      KeywordBlock b("*CONSTRAINED_EXTRA_NODES_SET");
      b.card(L::kExtraNodes, {lead, static_cast<long long>(sid)});
      emit(b);
    }
  }
}

void Composer::rigid_body_velocities() {
  // A body of nodes takes the velocity of the last card on its nodes (the reader's rule): its
  // own, written after every other initial velocity, even 0 (a weld at rest in a moving part).
  for (const auto& rb : m_.rigid_bodies) {
    if (!rb.parts.empty() || nodal_inertia_given(rb)) continue;  // *PART_INERTIA, _INERTIA
    const std::int64_t sid = node_set(rb.nodes, rb.name + " velocity");
    initial_velocity(sid, rb.velocity_m_s);
  }
}

void Composer::initial_velocity(std::int64_t sid, const Vec3& v_m_s) {
  KeywordBlock b("*INITIAL_VELOCITY");
  b.card(L::kInitialVelocity1, {static_cast<long long>(sid)});
  b.card(L::kInitialVelocity2, {velocity(v_m_s[0]), velocity(v_m_s[1]), velocity(v_m_s[2])});
  emit(b);
}

void Composer::constraints() {
  // One node set per combination of fixed dofs.
  std::map<std::uint8_t, std::vector<std::int32_t>> by_mask;
  for (std::size_t i = 0; i < m_.fixed.size(); ++i)
    if (m_.fixed[i] != 0) by_mask[m_.fixed[i]].push_back(static_cast<std::int32_t>(i));
  for (const auto& [mask, nodes] : by_mask) {
    std::string dofs;
    for (int d = 0; d < 6; ++d)
      if (mask & (1 << d))
        dofs += std::string(dofs.empty() ? "" : " ") + (d < 3 ? "" : "r") + "xyz"[d % 3];
    const std::int64_t sid = node_set(nodes, "fixed " + dofs);
    KeywordBlock b("*BOUNDARY_SPC_SET");
    std::vector<Value> v{static_cast<long long>(sid), 0};
    for (int d = 0; d < 6; ++d) v.emplace_back((mask & (1 << d)) ? 1 : 0);
    b.card(L::kSpcSet, std::move(v));
    emit(b);
  }
}

void Composer::initial_velocities() {
  std::vector<char> body_node(m_.nodes.count(), 0);
  for (const auto& rb : m_.rigid_bodies) {
    for (int p : rb.parts)
      for (auto c : m_.parts[static_cast<std::size_t>(p)].connectivity)
        body_node[static_cast<std::size_t>(c)] = 1;
    for (auto c : rb.nodes) body_node[static_cast<std::size_t>(c)] = 1;
  }
  for (std::size_t k = 0; k < m_.initial_velocities.size(); ++k) {
    const auto& iv = m_.initial_velocities[k];
    const Vec3& w = iv.angular_velocity_rad_s;
    const double omega = norm(w);
    if (omega == 0.0) {
      const std::int64_t sid = node_set(iv.nodes, fmt::format("initial velocity {}", k + 1));
      initial_velocity(sid, iv.velocity_m_s);
      continue;
    }
    // A spin: *INITIAL_VELOCITY_GENERATION on the node set (STYP 3), OMEGA about the axis
    // through the centre. The bodies' nodes are left out (a body keeps its own velocity, which
    // the reader would otherwise take from the spin).
    std::vector<std::int32_t> nodes;
    for (auto c : iv.nodes)
      if (!body_node[static_cast<std::size_t>(c)]) nodes.push_back(c);
    if (nodes.empty()) continue;
    const std::int64_t sid = node_set(nodes, fmt::format("initial velocity {}", k + 1));
    KeywordBlock b("*INITIAL_VELOCITY_GENERATION");
    b.card(L::kVelocityGeneration1,
           {static_cast<long long>(sid), 3, omega * u_.time_s, velocity(iv.velocity_m_s[0]),
            velocity(iv.velocity_m_s[1]), velocity(iv.velocity_m_s[2]), 0, 0});
    b.card(L::kVelocityGeneration2,
           {length(iv.centre_m[0]), length(iv.centre_m[1]), length(iv.centre_m[2]), w[0] / omega,
            w[1] / omega, w[2] / omega, 0, 0});
    emit(b);
  }
}

void Composer::curve_dofs() {
  for (const auto& pv : m_.prescribed_velocities) {
    const bool rotation = pv.dof >= 3;
    if (pv.rigid_body >= 0) {  // a body's: by its lead part (check_exportable: it has one)
      const auto& body = m_.rigid_bodies[static_cast<std::size_t>(pv.rigid_body)];
      const std::int64_t lcid = curve(pv.velocity, rotation ? 1.0 / u_.time_s : u_.velocity_m_s(),
                                      pv.name + (rotation ? " [rad/time]" : " [velocity]"));
      KeywordBlock b("*BOUNDARY_PRESCRIBED_MOTION_RIGID");
      b.card(L::kMotionRigid,
             {static_cast<long long>(part_id_[static_cast<std::size_t>(body.parts[0])]),
              rotation ? pv.dof + 2 : pv.dof + 1, 0, static_cast<long long>(lcid), 1.0});
      emit(b);
      continue;
    }
    const std::int64_t sid = node_set(pv.nodes, "prescribed " + pv.name);
    const std::int64_t lcid = curve(pv.velocity, rotation ? 1.0 / u_.time_s : u_.velocity_m_s(),
                                    pv.name + (rotation ? " [rad/time]" : " [velocity]"));
    KeywordBlock b("*BOUNDARY_PRESCRIBED_MOTION_SET");
    // DOF 1-3 translations, 5-7 rotations; VAD 0: velocity.
    b.card(L::kMotionSet, {static_cast<long long>(sid), rotation ? pv.dof + 2 : pv.dof + 1, 0,
                           static_cast<long long>(lcid), 1.0});
    emit(b);
  }
  for (const auto& ld : m_.loads) {
    const std::int64_t sid = node_set(ld.nodes, "load " + ld.name);
    const std::int64_t lcid = curve(ld.force, u_.force_N(), ld.name + " [force per node]");
    KeywordBlock b("*LOAD_NODE_SET");
    b.card(L::kLoadSet,
           {static_cast<long long>(sid), ld.dof + 1, static_cast<long long>(lcid), 1.0});
    emit(b);
  }
}

void Composer::contacts() {
  for (std::size_t k = 0; k < m_.contacts.size(); ++k) {
    const auto& c = m_.contacts[k];
    long long ssid = 0, msid = 0;
    int sstyp = 0, mstyp = 0;
    std::string kw;
    if (c.kind == model::ContactKind::SingleSurface) {
      kw = "*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID";
      ssid = part_set(c.master_parts, c.name + " surface");
      sstyp = 2;
    } else {
      kw = c.kind == model::ContactKind::NodeToSurface ? "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID"
                                                       : "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID";
      // The slave side: whole parts if the slave nodes are exactly some parts' nodes; else
      // (surface to surface) the faces made of slave nodes as a segment set, if they hold every
      // slave node; else a node set.
      const auto slave = sorted_unique(c.slave_nodes);
      std::vector<int> whole;
      std::vector<std::int32_t> covered;
      for (std::size_t p = 0; p < m_.parts.size(); ++p) {
        const auto n = part_nodes(m_.parts[p]);
        if (std::includes(slave.begin(), slave.end(), n.begin(), n.end())) {
          whole.push_back(static_cast<int>(p));
          covered.insert(covered.end(), n.begin(), n.end());
        }
      }
      std::vector<std::int32_t> faces;
      if (c.kind == model::ContactKind::SurfaceToSurface)
        faces =
            c.slave_faces.empty() ? contact::slave_faces(m_, slave, c.master_parts) : c.slave_faces;
      if (!whole.empty() && sorted_unique(covered) == slave && c.slave_faces.empty()) {
        ssid = part_set(whole, c.name + " slave parts");
        sstyp = 2;
      } else if (!faces.empty() && sorted_unique(faces) == slave) {
        const long long id = next_segment_set_++;
        KeywordBlock b("*SET_SEGMENT_TITLE");
        b.line(c.name + " slave faces");
        b.card(L::kSetHeader, {id});
        for (std::size_t f = 0; 4 * f < faces.size(); ++f)
          b.card(L::kSetSegment, {static_cast<long long>(node_id(faces[4 * f])),
                                  static_cast<long long>(node_id(faces[4 * f + 1])),
                                  static_cast<long long>(node_id(faces[4 * f + 2])),
                                  static_cast<long long>(node_id(faces[4 * f + 3]))});
        emit(b);
        ssid = id;
        sstyp = 0;
      } else {
        ssid = node_set(slave, c.name + " slave nodes");
        sstyp = 4;
        if (c.kind == model::ContactKind::SurfaceToSurface)
          notes_.push_back(fmt::format(
              "contact '{}': slave nodes that no face of their own holds are written as a node "
              "set (SSTYP 4), which LS-DYNA takes in NODES_TO_SURFACE contacts only",
              c.name));
      }
      msid = part_set(c.master_parts, c.name + " master parts");
      mstyp = 2;
    }
    KeywordBlock b(kw);
    b.card(L::kIdHeading, {static_cast<long long>(k + 1), c.name});
    b.card(L::kContact1, {ssid, msid, sstyp, mstyp});
    // crashlink's friction decays from FS to FD with DC [time/length]; with DC = 0 it is FS.
    const double fd = c.friction_decay_s_m > 0.0 ? c.dynamic_friction : c.static_friction;
    b.card(L::kContact2, {c.static_friction, fd, c.friction_decay_s_m * u_.length_m / u_.time_s});
    b.card(L::kContact3, {c.penalty_scale, c.penalty_scale, length(c.slave_thickness_m),
                          length(c.master_thickness_m)});
    b.card(L::kContactA, {c.soft ? 1 : 0, c.soft_scale});
    emit(b);
  }
}

void Composer::rigid_walls() {
  for (std::size_t k = 0; k < m_.rigid_walls.size(); ++k) {
    const auto& w = m_.rigid_walls[k];
    const std::int64_t sid = node_set(w.nodes, w.name + " nodes");
    const bool cylinder = w.shape == model::RigidWall::Shape::Cylinder;
    KeywordBlock b(cylinder     ? "*RIGIDWALL_GEOMETRIC_CYLINDER_ID"
                   : w.finite() ? (w.moving() ? "*RIGIDWALL_PLANAR_FINITE_MOVING_ID"
                                              : "*RIGIDWALL_PLANAR_FINITE_ID")
                   : w.moving() ? "*RIGIDWALL_PLANAR_MOVING_ID"
                                : "*RIGIDWALL_PLANAR_ID");
    b.card(L::kIdHeading, {static_cast<long long>(k + 1), w.name});
    b.card(cylinder ? deck::Layout(L::kRigidWallGeometric1) : deck::Layout(L::kRigidWall1),
           {static_cast<long long>(sid)});
    // Tail on the plane (the axis), head one length unit along the normal (the nodes' side; the
    // axis).
    const Vec3 t = w.point_m;
    b.card(L::kRigidWall2, {length(t[0]), length(t[1]), length(t[2]), length(t[0]) + w.normal[0],
                            length(t[1]) + w.normal[1], length(t[2]) + w.normal[2]});
    if (cylinder) b.card(L::kRigidWallCylinder, {length(w.radius_m), length(w.length_m)});
    // the edge l: its head one length unit from the tail along it
    if (!cylinder && w.finite())
      b.card(L::kRigidWallFinite,
             {length(t[0]) + w.edge[0], length(t[1]) + w.edge[1], length(t[2]) + w.edge[2],
              length(w.length_m), length(w.width_m)});
    if (w.moving()) b.card(L::kRigidWallMoving, {mass(w.mass_kg), velocity(w.velocity_m_s)});
    emit(b);
  }
}

void Composer::probes() {
  bool rigid = false;
  for (const auto& p : m_.probes) {
    if (p.kind == model::Probe::Kind::RigidBody) {
      rigid = true;
      // the deck's body: named after its lead part, or a nodal rigid body's title
      const auto& body = m_.rigid_bodies[static_cast<std::size_t>(p.index)];
      const std::string& deck_name =
          body.parts.empty() ? body.name : m_.parts[static_cast<std::size_t>(body.parts[0])].name;
      if (p.name != deck_name)
        notes_.push_back(
            fmt::format("probe '{}' of rigid body '{}' is named '{}' in the deck "
                        "(*DATABASE_RBDOUT names each body after its part)",
                        p.name, body.name, deck_name));
      continue;
    }
    KeywordBlock b("*DATABASE_HISTORY_NODE_ID");
    b.card(L::kIdHeading, {static_cast<long long>(node_id(p.index)), p.name});
    emit(b);
  }
  const double dt = time(m_.controls.history_interval_s);
  if (rigid) {
    // *DATABASE_RBDOUT probes every body: those the model does not probe gain one
    std::vector<char> probed(m_.rigid_bodies.size(), 0);
    for (const auto& p : m_.probes)
      if (p.kind == model::Probe::Kind::RigidBody) probed[static_cast<std::size_t>(p.index)] = 1;
    std::string extra;
    for (std::size_t b = 0; b < probed.size(); ++b)
      if (!probed[b]) extra += (extra.empty() ? "'" : ", '") + m_.rigid_bodies[b].name + "'";
    if (!extra.empty())
      notes_.push_back("*DATABASE_RBDOUT probes every rigid body: " + extra +
                       " gain a probe in the deck");
    KeywordBlock b("*DATABASE_RBDOUT");  // every rigid body's motion: crashlink's body probes
    b.card(L::kDatabaseAscii, {dt});
    emit(b);
  }
  bool nodes = false;
  for (const auto& p : m_.probes) nodes = nodes || p.kind == model::Probe::Kind::Node;
  if (nodes) {
    KeywordBlock b("*DATABASE_NODOUT");
    b.card(L::kDatabaseAscii, {dt});
    emit(b);
  }
}

}  // namespace crashlink::deck_writer::detail
