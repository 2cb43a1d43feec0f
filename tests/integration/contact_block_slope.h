#pragma once
// A block of hexahedra on a fixed shell plane inclined at theta about the y axis, under gravity
// (0, 0, -g), Coulomb friction (issue 21, acceptance item 5). Downhill direction
// s = (cos theta, 0, -sin theta), plane normal n = (sin theta, 0, cos theta) = s x e_y (the plate
// generator's normal edge1 x edge2). The block is built in slope coordinates (X along s, Y along
// y, Z along n) and turned with the plane (a proper rotation: its hexes keep positive Jacobians);
// its lower face lies on the plate's offset surface (half the plate thickness above the mid-plane).
// theta = 0 is the flat sliding block of contact_friction_test.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "solver/integration/solver.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"
#include "tests/integration/test_models.h"

namespace crashlink::testing {

struct BlockSlopeSpec {
  double theta_deg = 30.0;
  double mu_s = 0.3, mu_d = 0.3, decay_s_m = 0.0;  ///< model::Contact's friction law
  double g_m_s2 = 9.81;
  double v0_m_s = 0.0;  ///< initial speed down the slope
  model::ContactKind kind = model::ContactKind::NodeToSurface;
  /// > 0: gravity on the block as nodal loads m_i g ramped from 0 over this time instead of
  /// Model::controls.gravity_m_s2 (the plate is fixed: gravity on it does nothing)
  double gravity_ramp_s = 0.0;
  double end_time_s = 0.2;
  double plate_thickness_m = 0.002;
  // Soft rubber-like material for both (E 1e7 Pa, 1000 kg/m^3): a few thousand steps to 0.2 s.
  double density_kg_m3 = 1000.0, youngs_Pa = 1e7;
};

struct BlockSlope {
  model::Model m;
  std::vector<std::int32_t> block;  ///< node indices of the block
  Vec3 downhill{}, normal{};
};

inline BlockSlope make_block_slope(const BlockSlopeSpec& s) {
  BlockSlope b;
  auto& m = b.m;
  m.name = "block on slope";
  m.materials.push_back(
      {"soft", materials::MaterialKind::Elastic, s.density_kg_m3, s.youngs_Pa, 0.3, {}});
  const double th = s.theta_deg * M_PI / 180.0;
  b.downhill = {std::cos(th), 0.0, -std::sin(th)};
  b.normal = {std::sin(th), 0.0, std::cos(th)};
  const Vec3 ey{0.0, 1.0, 0.0};
  // plane: X in [-0.05, 0.55] m along s, Y in [-0.1, 0.1] m; 50 mm shells
  model::Part plate;
  plate.name = "slope";
  plate.material = 0;
  plate.thickness_m = s.plate_thickness_m;
  model::generate_plate(
      m, plate, {-0.05 * b.downhill + (-0.1) * ey, 0.6 * b.downhill, 0.2 * ey, {12, 4}, 0.0});
  const std::size_t n_plate = m.nodes.count();
  // block 40 x 40 x 20 mm, 2 x 2 x 1 hexes, its lower face on the plate's offset surface
  model::Part block;
  block.name = "block";
  block.material = 0;
  model::generate_box(m, block,
                      {{0.0, -0.02, 0.5 * s.plate_thickness_m}, {0.04, 0.04, 0.02}, {2, 2, 1}});
  for (std::size_t i = n_plate; i < m.nodes.count(); ++i) {
    double* x = &m.nodes.x0[3 * i];
    const Vec3 p = x[0] * b.downhill + x[1] * ey + x[2] * b.normal;
    x[0] = p[0], x[1] = p[1], x[2] = p[2];
    b.block.push_back(static_cast<std::int32_t>(i));
  }
  m.fixed.assign(m.nodes.count(), 0);
  for (std::size_t i = 0; i < n_plate; ++i) m.fixed[i] = 63;
  if (s.v0_m_s != 0.0) m.initial_velocities.push_back({b.block, s.v0_m_s * b.downhill});
  model::Contact c;
  c.name = "block-slope";
  c.kind = s.kind;
  c.slave_nodes = b.block;
  c.master_parts = {0};
  c.static_friction = s.mu_s;
  c.dynamic_friction = s.mu_d;
  c.friction_decay_s_m = s.decay_s_m;
  m.contacts.push_back(c);
  m.controls.end_time_s = s.end_time_s;
  if (s.gravity_ramp_s <= 0.0) {
    m.controls.gravity_m_s2 = {0.0, 0.0, -s.g_m_s2};
    return b;
  }
  // the lumped masses from a solver of the model as built so far
  std::vector<double> mass;
  {
    integration::Solver probe(m, "masses");
    probe.initialize();
    mass = probe.mass();
  }
  // one load per dof and per distinct nodal mass (a NodalLoad puts the same force on every node)
  std::vector<std::pair<double, std::vector<std::int32_t>>> groups;
  for (auto i : b.block) {
    const double mi = mass[static_cast<std::size_t>(i)];
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const auto& g) { return std::fabs(g.first - mi) <= 1e-12 * mi; });
    if (it == groups.end()) groups.push_back({mi, {}}), it = groups.end() - 1;
    it->second.push_back(i);
  }
  for (const auto& [mi, nodes] : groups)
    m.loads.push_back(
        {"gravity", nodes, 2, model::Curve{{0.0, s.gravity_ramp_s}, {0.0, -mi * s.g_m_s2}}});
  return b;
}

}  // namespace crashlink::testing
