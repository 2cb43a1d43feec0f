#pragma once
// Issue 21, acceptance item 4: a rigid sphere dropped square onto the centre of a clamped steel
// plate. The scene is symmetric about the planes x = 0 and y = 0 (the sphere's lowest node sits
// over the plate's centre node, both meshes are symmetric about these planes), so the sphere must
// leave along z: any lateral velocity is made by the contact (an order-dependent search, a tie
// broken by index, an edge choice that depends on the side), not by the physics.
//
// Sphere: shell cube-sphere (generate_sphere), one rigid body; plate: Shell4 (generate_plate),
// clamped (all six dofs) along its four edges; plate nodes are the slave side, the sphere's
// segments the master (as scenarios/plate_impact.yaml). Frictionless, penalty_scale 0.1.
// Defaults: the scene of contact_sphere_plate_test.cpp (0.5 m plate, 0.6 kg ball: what reproduces
// the 200 x 200 numbers on today's code).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"
#include "tests/integration/test_models.h"

namespace crashlink::testing {

struct SpherePlateSpec {
  double plate_side_m = 0.5;  ///< square plate, centred on the origin in the x-y plane
  int plate_divisions = 200;  ///< elements along each edge (even: a node at the centre)
  double plate_thickness_m = 0.001;
  bool j2 = false;  ///< plate material: test_models.h j2_steel() instead of steel()
  double radius_m = 0.025;
  int sphere_divisions = 8;           ///< generate_sphere n (even: a node at the lowest point)
  double sphere_thickness_m = 0.001;  ///< contact offset (and element mass if mass_kg is 0)
  double sphere_mass_kg = 0.6;        ///< > 0: the rigid body's mass (inertia 2/5 m R^2 then)
  double speed_m_s = 10.0;            ///< along -z
  double gap_m = 1e-4;                ///< between the offset surfaces at t = 0
  double penalty_scale = 0.1;
  model::ContactKind kind = model::ContactKind::SurfaceToSurface;  ///< the scenario default
  double end_time_s = 6e-3;
  double dt_scale = 0.9;
};

struct SpherePlate {
  model::Model m;
  std::int32_t centre = -1;     ///< the plate's centre node
  std::size_t plate_nodes = 0;  ///< plate nodes are [0, plate_nodes)
};

inline SpherePlate make_sphere_plate(const SpherePlateSpec& s) {
  SpherePlate b;
  auto& m = b.m;
  m.name = "sphere on plate";
  m.materials.push_back(s.j2 ? j2_steel() : steel());
  m.materials.push_back({"rigid", materials::MaterialKind::Rigid, 7850.0, 210e9, 0.3, {}});
  model::Part plate;
  plate.name = "plate";
  plate.material = 0;
  plate.thickness_m = s.plate_thickness_m;
  const double a = s.plate_side_m;
  model::generate_plate(m, plate,
                        {{-0.5 * a, -0.5 * a, 0.0},
                         {a, 0.0, 0.0},
                         {0.0, a, 0.0},
                         {s.plate_divisions, s.plate_divisions},
                         0.0});
  b.plate_nodes = m.nodes.count();
  model::Part ball;
  ball.name = "sphere";
  ball.material = 1;
  ball.thickness_m = s.sphere_thickness_m;
  const double zc = s.radius_m + 0.5 * (s.plate_thickness_m + s.sphere_thickness_m) + s.gap_m;
  model::generate_sphere(m, ball, {{0.0, 0.0, zc}, s.radius_m, s.sphere_divisions});
  m.fixed.assign(m.nodes.count(), 0);
  const double tol = 1e-6 * a;
  for (std::size_t i = 0; i < b.plate_nodes; ++i) {
    const double x = m.nodes.x0[3 * i], y = m.nodes.x0[3 * i + 1];
    if (std::fabs(std::fabs(x) - 0.5 * a) < tol || std::fabs(std::fabs(y) - 0.5 * a) < tol)
      m.fixed[i] = 63;
    if (std::fabs(x) < tol && std::fabs(y) < tol) b.centre = static_cast<std::int32_t>(i);
  }
  model::RigidBody rb;
  rb.name = "sphere";
  rb.parts = {1};
  rb.velocity_m_s = {0.0, 0.0, -s.speed_m_s};
  if (s.sphere_mass_kg > 0.0) {
    rb.mass_kg = s.sphere_mass_kg;
    const double J = 0.4 * s.sphere_mass_kg * s.radius_m * s.radius_m;
    rb.inertia_given = true;
    rb.inertia_kg_m2 = {{{J, 0.0, 0.0}, {0.0, J, 0.0}, {0.0, 0.0, J}}};
    rb.centre_given = true;
    rb.centre_m = {0.0, 0.0, zc};
  }
  m.rigid_bodies.push_back(rb);
  model::Contact c;
  c.name = "sphere-plate";
  c.kind = s.kind;
  for (std::size_t i = 0; i < b.plate_nodes; ++i)
    c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  c.master_parts = {1};
  c.penalty_scale = s.penalty_scale;
  m.contacts.push_back(c);
  m.controls.end_time_s = s.end_time_s;
  m.controls.dt_scale = s.dt_scale;
  return b;
}

}  // namespace crashlink::testing
