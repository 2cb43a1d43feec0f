#include "solver/model/model.h"

#include <cmath>

#include "solver/core/errors.h"

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
  if (!(m.controls.end_time_s > 0.0))
    throw ModelError(fmt::format("controls: end time {} s must be > 0", m.controls.end_time_s));
  if (!(m.controls.dt_scale > 0.0))
    throw ModelError(
        fmt::format("controls: dt scale {} must be > 0 (default 0.9)", m.controls.dt_scale));
}

}  // namespace crashlink::model
