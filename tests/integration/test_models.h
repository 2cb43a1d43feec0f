#pragma once
// Small models built in code for the physics acceptance tests (no scenario file needed).
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"

namespace crashlink::testing {

inline materials::Material steel(double nu = 0.3) {
  return {"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, nu, {}};
}

/// J2 steel: yield 200 MPa, hardening to 300 MPa at eps_p 0.1, then 400 MPa at 0.5.
inline materials::Material j2_steel() {
  return {"j2", materials::MaterialKind::J2Plastic,      7850.0, 210e9,
          0.3,  {{0.0, 0.1, 0.5}, {200e6, 300e6, 400e6}}};
}

/// Indices of the nodes whose reference position satisfies `pred`.
inline std::vector<std::int32_t> nodes_where(const model::Model& m,
                                             const std::function<bool(const Vec3&)>& pred) {
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (pred({m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]}))
      out.push_back(static_cast<std::int32_t>(i));
  return out;
}

inline void fix(model::Model& m, const std::vector<std::int32_t>& nodes, std::uint8_t mask) {
  if (m.fixed.empty()) m.fixed.assign(m.nodes.count(), 0);
  for (auto i : nodes) m.fixed[static_cast<std::size_t>(i)] |= mask;
}

inline int add_probe(model::Model& m, const std::string& name, std::int32_t node) {
  m.probes.push_back({name, model::Probe::Kind::Node, node});
  return static_cast<int>(m.probes.size()) - 1;
}

/// One row of `n` hexes along +x, square cross-section `a` (m), material `mat`.
inline model::Model bar(int n, double length, double a, const materials::Material& mat) {
  model::Model m;
  m.name = "bar";
  m.materials.push_back(mat);
  model::Part p;
  p.name = "bar";
  p.material = 0;
  model::generate_box(m, p, {{0.0, 0.0, 0.0}, {length, a, a}, {n, 1, 1}});
  m.fixed.assign(m.nodes.count(), 0);
  return m;
}

/// Cantilever strip of shells in the x-y plane, clamped at x = 0 (all 6 dofs).
inline model::Model shell_cantilever(double length, double width, double thickness, int nx, int ny,
                                     const materials::Material& mat) {
  model::Model m;
  m.name = "shell cantilever";
  m.materials.push_back(mat);
  model::Part p;
  p.name = "strip";
  p.material = 0;
  p.thickness_m = thickness;
  p.through_thickness_points = 5;
  model::generate_plate(m, p,
                        {{0.0, 0.0, 0.0}, {length, 0.0, 0.0}, {0.0, width, 0.0}, {nx, ny}, 0.0});
  fix(m, nodes_where(m, [](const Vec3& x) { return x[0] < 1e-9; }), 63);
  return m;
}

/// Cantilever beam of hexes along x, clamped at x = 0.
inline model::Model hex_cantilever(double length, double width, double thickness, int nx, int ny,
                                   int nz, const materials::Material& mat) {
  model::Model m;
  m.name = "hex cantilever";
  m.materials.push_back(mat);
  model::Part p;
  p.name = "beam";
  p.material = 0;
  model::generate_box(m, p, {{0.0, 0.0, 0.0}, {length, width, thickness}, {nx, ny, nz}});
  fix(m, nodes_where(m, [](const Vec3& x) { return x[0] < 1e-9; }), 7);
  return m;
}

/// A steel hex block (origin, size, divisions) clamped at its face x = origin_x, every node
/// started with velocity v + omega x (x - centre): the threads tests' scene (solver_threads_test,
/// solver_threads_alloc_test).
inline model::Model clamped_moving_block(const Vec3& origin, const Vec3& size,
                                         std::array<int, 3> divisions, const Vec3& velocity,
                                         const Vec3& omega, const Vec3& centre = {}) {
  model::Model m;
  m.name = "clamped moving block";
  m.materials.push_back(steel());
  model::Part p;
  p.name = "block";
  p.material = 0;
  model::generate_box(m, p, {origin, size, divisions});
  fix(m, nodes_where(m, [&](const Vec3& x) { return x[0] < origin[0] + 1e-9; }), 7);
  model::InitialVelocity iv;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    iv.nodes.push_back(static_cast<std::int32_t>(i));
  iv.velocity_m_s = velocity;
  iv.angular_velocity_rad_s = omega;
  iv.centre_m = centre;
  m.initial_velocities.push_back(iv);
  m.controls.end_time_s = 1.0;
  return m;
}

}  // namespace crashlink::testing
