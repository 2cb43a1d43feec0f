#include "solver/model/model.h"

#include <cmath>

#include "core/errors.h"

namespace crashlink::model {

int Model::node_index(std::int64_t id) const {
  for (std::size_t i = 0; i < nodes.id.size(); ++i)
    if (nodes.id[i] == id) return static_cast<int>(i);
  return -1;
}

int Model::part_index(const std::string& part_name) const {
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (parts[i].name == part_name) return static_cast<int>(i);
  return -1;
}

std::size_t Model::element_count() const {
  std::size_t n = 0;
  for (const auto& p : parts) n += p.element_count();
  return n;
}

void validate(const Model& m) {
  const std::size_t n = m.nodes.count();
  if (m.nodes.x0.size() != 3 * n)
    throw ModelError(
        fmt::format("nodes: {} ids but {} coordinates (need 3 per node)", n, m.nodes.x0.size()));
  for (double x : m.nodes.x0)
    if (!std::isfinite(x)) throw ModelError("nodes: a coordinate is not finite");
  if (!m.fixed.empty() && m.fixed.size() != n)
    throw ModelError(fmt::format("fixed: {} masks for {} nodes", m.fixed.size(), n));
  for (const auto& mat : m.materials) materials::validate(mat);
  for (const auto& p : m.parts) {
    const std::size_t k = static_cast<std::size_t>(nodes_per_element(p.kind));
    if (p.material < 0 || p.material >= static_cast<int>(m.materials.size()))
      throw ModelError(fmt::format("part '{}': material index {} out of range (have {})", p.name,
                                   p.material, m.materials.size()));
    if (p.connectivity.size() % k != 0)
      throw ModelError(fmt::format("part '{}': connectivity size {} is not a multiple of {}",
                                   p.name, p.connectivity.size(), k));
    if (p.element_id.size() != p.element_count())
      throw ModelError(fmt::format("part '{}': {} element ids for {} elements", p.name,
                                   p.element_id.size(), p.element_count()));
    for (auto c : p.connectivity)
      if (c < 0 || static_cast<std::size_t>(c) >= n)
        throw ModelError(
            fmt::format("part '{}': node index {} out of range (have {} nodes)", p.name, c, n));
    if (p.kind == ElementKind::Shell4) {
      if (!(p.thickness_m > 0.0))
        throw ModelError(
            fmt::format("part '{}': shell thickness {} m must be > 0", p.name, p.thickness_m));
      if (p.through_thickness_points < 3 || p.through_thickness_points > 9)
        throw ModelError(
            fmt::format("part '{}': {} points through the thickness; use 3 to 9 (5 for plasticity)",
                        p.name, p.through_thickness_points));
    }
    if (p.hourglass_coefficient < 0.0 || p.hourglass_coefficient > 0.3)
      throw ModelError(fmt::format("part '{}': hourglass coefficient {} outside [0, 0.3]", p.name,
                                   p.hourglass_coefficient));
    // Stiffness-proportional damping (Part::damping_ratio): a fraction of critical at the highest
    // frequency; above 0.5 the stable step falls below 0.62 of the undamped one and the low modes
    // are barely damped anyway (xi_k = xi omega_k / omega_max).
    const auto bad_ratio = [](double xi) { return !(xi >= 0.0 && xi <= 0.5); };
    if (bad_ratio(p.damping_ratio))
      throw ModelError(fmt::format(
          "part '{}': damping ratio {} outside [0, 0.5]; give the fraction of critical damping at "
          "the element's highest frequency, e.g. 0.05 (0: no damping)",
          p.name, p.damping_ratio));
    if (!p.element_thickness_m.empty()) {
      if (p.kind != ElementKind::Shell4 || p.element_thickness_m.size() != p.element_count())
        throw ModelError(fmt::format(
            "part '{}': {} element thicknesses for {} elements of a {} part (internal error: one "
            "per shell element)",
            p.name, p.element_thickness_m.size(), p.element_count(),
            p.kind == ElementKind::Shell4 ? "shell" : "solid"));
      for (std::size_t e = 0; e < p.element_thickness_m.size(); ++e)
        if (!(p.element_thickness_m[e] > 0.0))
          throw ModelError(fmt::format("part '{}', shell element {}: thickness {} m must be > 0",
                                       p.name, p.element_id[e], p.element_thickness_m[e]));
    }
    if (!p.element_damping_ratio.empty()) {
      if (p.element_damping_ratio.size() != p.element_count())
        throw ModelError(fmt::format(
            "part '{}': {} per-element damping ratios for {} elements; give one per element or "
            "none (then damping_ratio {} applies to all)",
            p.name, p.element_damping_ratio.size(), p.element_count(), p.damping_ratio));
      for (std::size_t e = 0; e < p.element_damping_ratio.size(); ++e)
        if (bad_ratio(p.element_damping_ratio[e]))
          throw ModelError(fmt::format(
              "part '{}' element {}: damping ratio {} outside [0, 0.5]; use e.g. 0.05 (0: none)",
              p.name, p.element_id[e], p.element_damping_ratio[e]));
    }
    if (!p.element_density_scale.empty()) {
      if (p.element_density_scale.size() != p.element_count())
        throw ModelError(
            fmt::format("part '{}': {} density factors for {} elements (internal "
                        "error of the mass scaling)",
                        p.name, p.element_density_scale.size(), p.element_count()));
      for (std::size_t e = 0; e < p.element_density_scale.size(); ++e)
        if (!(p.element_density_scale[e] >= 1.0) || !std::isfinite(p.element_density_scale[e]))
          throw ModelError(fmt::format(
              "part '{}' element {}: density factor {} of the mass scaling must be >= 1 and "
              "finite (internal error)",
              p.name, p.element_id[e], p.element_density_scale[e]));
    }
    if (p.damped() &&
        m.materials[static_cast<std::size_t>(p.material)].kind == materials::MaterialKind::Rigid)
      throw ModelError(
          fmt::format("part '{}': damping ratio on rigid material '{}' has no effect; remove it",
                      p.name, m.materials[static_cast<std::size_t>(p.material)].name));
  }
  for (const auto& rb : m.rigid_bodies) {
    if (rb.parts.empty() && rb.nodes.empty())
      throw ModelError(
          fmt::format("rigid body '{}' has neither parts nor nodes; give it rigid "
                      "parts or the nodes that follow it",
                      rb.name));
    for (auto i : rb.nodes)
      if (i < 0 || static_cast<std::size_t>(i) >= m.nodes.count())
        throw ModelError(fmt::format("rigid body '{}': node index {} out of range", rb.name, i));
    if (rb.failure.any() && rb.fixed != 0)
      throw ModelError(
          fmt::format("spot weld '{}': holds some of its dofs; a weld that lets go cannot be held "
                      "(fix: hold the sheets' nodes, not the weld)",
                      rb.name));
    if (rb.failure.any() && (!rb.parts.empty() || rb.nodes.size() != 2))
      throw ModelError(
          fmt::format("rigid body '{}': a failure criterion belongs to a spot weld "
                      "of two nodes and no part (it has {} nodes, {} parts)",
                      rb.name, rb.nodes.size(), rb.parts.size()));
    if (rb.failure.any() && rb.nodes.size() == 2) {
      double gap = 0.0;
      for (std::size_t d = 0; d < 3; ++d) {
        const double x = m.nodes.x0[3 * static_cast<std::size_t>(rb.nodes[0]) + d] -
                         m.nodes.x0[3 * static_cast<std::size_t>(rb.nodes[1]) + d];
        gap += x * x;
      }
      if (!(gap > 0.0))
        throw ModelError(
            fmt::format("spot weld '{}': its two nodes lie at one place; a weld's "
                        "normal runs from one to the other: weld nodes apart",
                        rb.name));
    }
    if (!(rb.failure.normal_N >= 0.0 && rb.failure.shear_N >= 0.0 && rb.failure.exp_n > 0.0 &&
          rb.failure.exp_m > 0.0 && rb.failure.time_s >= 0.0))
      throw ModelError(
          fmt::format("spot weld '{}': strengths {} N, {} N and time {} s must be "
                      ">= 0, the exponents {}, {} > 0",
                      rb.name, rb.failure.normal_N, rb.failure.shear_N, rb.failure.time_s,
                      rb.failure.exp_n, rb.failure.exp_m));
  }
  for (const auto& rb : m.rigid_bodies)
    for (int pi : rb.parts) {
      if (pi < 0 || pi >= static_cast<int>(m.parts.size()))
        throw ModelError(fmt::format("rigid body '{}': part index {} out of range", rb.name, pi));
      const auto& mat =
          m.materials[static_cast<std::size_t>(m.parts[static_cast<std::size_t>(pi)].material)];
      if (mat.kind != materials::MaterialKind::Rigid)
        throw ModelError(
            fmt::format("rigid body '{}': part '{}' has material '{}' which is not rigid", rb.name,
                        m.parts[static_cast<std::size_t>(pi)].name, mat.name));
    }
  for (const auto& w : m.rigid_walls) {
    if (std::abs(norm(w.normal) - 1.0) > 1e-9)
      throw ModelError(
          fmt::format("rigid wall '{}': normal ({}, {}, {}) is not a unit vector (internal error)",
                      w.name, w.normal[0], w.normal[1], w.normal[2]));
    for (auto i : w.nodes)
      if (i < 0 || static_cast<std::size_t>(i) >= m.nodes.count())
        throw ModelError(fmt::format("rigid wall '{}': node index {} out of range", w.name, i));
    const bool cylinder = w.shape == RigidWall::Shape::Cylinder;
    if (cylinder ? !(w.radius_m > 0.0) || w.moving() || !(w.length_m >= 0.0)
                 : !(w.length_m >= 0.0) || !(w.width_m >= 0.0) ||
                       (w.length_m > 0.0) != (w.width_m > 0.0) ||
                       (w.finite() && (std::abs(norm(w.edge) - 1.0) > 1e-9 ||
                                       std::abs(dot(w.edge, w.normal)) > 1e-9)))
      throw ModelError(fmt::format(
          "rigid wall '{}': {} with radius {} m, length {} m, width {} m, edge ({}, {}, {}); a "
          "cylinder has a radius > 0, a length >= 0 (0: infinite) and does not move; a finite "
          "plane a length and width > 0 and a unit edge in the plane",
          w.name, cylinder ? "cylinder" : "plane", w.radius_m, w.length_m, w.width_m, w.edge[0],
          w.edge[1], w.edge[2]));
    if (!(w.mass_kg >= 0.0) || !std::isfinite(w.velocity_m_s) ||
        (w.mass_kg == 0.0 && w.velocity_m_s != 0.0))
      throw ModelError(fmt::format(
          "rigid wall '{}': mass {} kg, velocity {} m/s; a fixed wall has mass 0 and no "
          "velocity, a moving one a mass > 0 (fix: give the moving wall's mass)",
          w.name, w.mass_kg, w.velocity_m_s));
  }
  for (const auto& pv : m.prescribed_velocities) {
    if (pv.dof < 0 || pv.dof > 5)
      throw ModelError(
          fmt::format("prescribed velocity '{}': dof {} outside 0..5", pv.name, pv.dof));
    if (pv.rigid_body >= 0 && pv.rigid_body < static_cast<int>(m.rigid_bodies.size()) &&
        m.rigid_bodies[static_cast<std::size_t>(pv.rigid_body)].failure.any())
      throw ModelError(fmt::format(
          "prescribed velocity '{}' drives spot weld '{}'; a weld that lets go cannot be driven "
          "(fix: drive the sheets' nodes)",
          pv.name, m.rigid_bodies[static_cast<std::size_t>(pv.rigid_body)].name));
    if (pv.rigid_body >= static_cast<int>(m.rigid_bodies.size()) ||
        (pv.rigid_body >= 0 && !pv.nodes.empty()))
      throw ModelError(fmt::format(
          "prescribed velocity '{}': rigid body index {} of {} (with {} nodes); a body's motion "
          "names one of the model's bodies and no node (internal error)",
          pv.name, pv.rigid_body, m.rigid_bodies.size(), pv.nodes.size()));
  }
  const auto& idamp = m.coupling.interface_damping;
  if (!(idamp.ratio >= 0.0 && idamp.ratio <= 0.5))
    throw ModelError(fmt::format(
        "coupling: interface damping ratio {} outside [0, 0.5]; give the fraction of critical "
        "damping at the element's highest frequency, e.g. 0.06 (0: off)",
        idamp.ratio));
  if (idamp.layers < 1)
    throw ModelError(
        fmt::format("coupling: interface damping over {} element layers; give at least 1 (e.g. 3)",
                    idamp.layers));
  if (!(m.controls.end_time_s > 0.0))
    throw ModelError(fmt::format("controls: end time {} s must be > 0", m.controls.end_time_s));
  if (!(m.controls.dt_scale > 0.0))
    throw ModelError(
        fmt::format("controls: dt scale {} must be > 0 (default 0.9)", m.controls.dt_scale));
}

}  // namespace crashlink::model
