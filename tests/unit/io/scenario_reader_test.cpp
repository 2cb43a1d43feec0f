#include "solver/io/scenario_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/errors.h"

namespace crashlink::io {
namespace {

using model::ElementKind;
using model::Model;

std::string scenario_path(const std::string& name) {
  return std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/" + name;
}

TEST(ScenarioReader, EveryExampleScenarioParses) {
  int count = 0;
  for (const auto& f :
       std::filesystem::directory_iterator(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios")) {
    if (f.path().extension() != ".yaml") continue;
    SCOPED_TRACE(f.path().string());
    EXPECT_NO_THROW({
      const Model m = read_scenario(f.path().string());
      EXPECT_GT(m.element_count(), 0u);
    });
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(ScenarioReader, BarWave) {
  const Model m = read_scenario(scenario_path("bar_wave.yaml"));
  EXPECT_EQ(m.name, "bar_wave");
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].kind, ElementKind::Hex8);
  EXPECT_EQ(m.parts[0].element_count(), 100u);
  EXPECT_EQ(m.nodes.count(), 101u * 4u);
  ASSERT_EQ(m.prescribed_velocities.size(), 1u);
  const auto& pv = m.prescribed_velocities[0];
  EXPECT_EQ(pv.name, "pulse");
  EXPECT_EQ(pv.dof, 0);
  EXPECT_EQ(pv.nodes.size(), 4u);  // the end face
  EXPECT_DOUBLE_EQ(pv.velocity.at(1e-5), 1.0);
  EXPECT_DOUBLE_EQ(pv.velocity.at(1e-4), 0.0);
  ASSERT_EQ(m.probes.size(), 3u);
  const auto mid = static_cast<std::size_t>(m.probes[0].index);
  EXPECT_EQ(m.probes[0].name, "middle");
  EXPECT_NEAR(m.nodes.x0[3 * mid], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(m.controls.end_time_s, 2.5e-4);
  EXPECT_DOUBLE_EQ(m.controls.dt_scale, 0.9);  // default
}

TEST(ScenarioReader, CantileverPlate) {
  const Model m = read_scenario(scenario_path("cantilever_plate.yaml"));
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].kind, ElementKind::Shell4);
  EXPECT_DOUBLE_EQ(m.parts[0].thickness_m, 0.002);
  EXPECT_EQ(m.parts[0].element_count(), 150u);
  int clamped = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (m.fixed[i] == 63) {
      ++clamped;
      EXPECT_NEAR(m.nodes.x0[3 * i], 0.0, 1e-15);
    }
  EXPECT_EQ(clamped, 6);
  ASSERT_EQ(m.loads.size(), 1u);
  EXPECT_EQ(m.loads[0].dof, 2);
  EXPECT_EQ(m.loads[0].nodes.size(), 6u);
  EXPECT_DOUBLE_EQ(m.loads[0].force.at(0.0025), 0.5);
}

TEST(ScenarioReader, PlateImpact) {
  const Model m = read_scenario(scenario_path("plate_impact.yaml"));
  ASSERT_EQ(m.parts.size(), 2u);
  const auto& plate = m.parts[0];
  const auto& ball = m.parts[1];
  EXPECT_EQ(plate.element_count(), 1600u);
  EXPECT_DOUBLE_EQ(plate.thickness_m, 7e-4);
  EXPECT_EQ(m.materials[static_cast<std::size_t>(plate.material)].kind,
            materials::MaterialKind::J2Plastic);
  EXPECT_EQ(ball.element_count(), 6u * 144u);
  EXPECT_EQ(m.nodes.count(), 41u * 41u + 6u * 144u + 2u);
  // Ids unique across parts: the sphere's nodes and elements continue the plate's numbering.
  EXPECT_EQ(m.nodes.id[41 * 41], 41 * 41 + 1);
  EXPECT_EQ(ball.element_id.front(), 1601);
  int clamped = 0;
  for (auto f : m.fixed) clamped += f == 63 ? 1 : 0;
  EXPECT_EQ(clamped, 160);  // the plate's perimeter
  ASSERT_EQ(m.rigid_bodies.size(), 1u);
  const auto& rb = m.rigid_bodies[0];
  EXPECT_EQ(rb.parts, std::vector<int>{1});
  EXPECT_DOUBLE_EQ(rb.mass_kg, 4.5);
  EXPECT_DOUBLE_EQ(rb.velocity_m_s[2], -9.72);
  EXPECT_TRUE(rb.inertia_given);
  EXPECT_DOUBLE_EQ(rb.inertia_kg_m2[1][1], 0.01225);
  EXPECT_EQ(rb.inertia_kg_m2[0][1], 0.0);
  ASSERT_EQ(m.probes.size(), 2u);
  EXPECT_EQ(m.probes[0].kind, model::Probe::Kind::RigidBody);
  EXPECT_EQ(m.probes[0].index, 0);
  const auto c = static_cast<std::size_t>(m.probes[1].index);
  EXPECT_NEAR(std::hypot(m.nodes.x0[3 * c], m.nodes.x0[3 * c + 1]), 0.0, 1e-12);
  // The headform sits above the plate (no overlap before contact exists).
  for (std::size_t i = 41 * 41; i < m.nodes.count(); ++i) EXPECT_GT(m.nodes.x0[3 * i + 2], 1e-3);
}

const char* kTwoBlocks = R"(name: merged
controls:
  end_time: 1.0e-3
  bulk_viscosity: {enabled: false, q_linear: 0.1, linear_in_expansion: true}
  gravity: [0, 0, -9.81]
materials:
  steel:
    type: j2
    density: 7850.0
    youngs_modulus: 2.0e+11
    poisson_ratio: 0.3
    yield_stress: 2.0e+8
    tangent_modulus: 2.0e+9
parts:
  a:
    material: steel
    mesh: {generator: box, size: [1, 1, 1], divisions: [2, 2, 2]}
  b:
    material: steel
    hourglass: 0.05
    merge_nodes: true
    mesh: {generator: box, origin: [1, 0, 0], size: [1, 1, 1], divisions: [2, 2, 2]}
node_sets:
  both_ends:
    - {box: {min: [0, 0, 0], max: [0, 1, 1]}}
    - {box: {min: [2, 0, 0], max: [2, 1, 1]}}
boundary:
  - nodes: both_ends
    fix: [x, rz]
initial_velocity:
  - part: b
    velocity: [1.0, 0, 0]
loads:
  - nodes: {nodes: [1, 2]}
    dof: y
    force: 3.5
probes:
  corner: {node: 1}
)";

TEST(ScenarioReader, MergedPartsShorthandsAndInlineSelections) {
  const Model m = parse_scenario(kTwoBlocks, "two_blocks.yaml");
  EXPECT_EQ(m.name, "merged");
  EXPECT_EQ(m.nodes.count(), 27u + 18u);  // the shared 3 x 3 face is merged
  EXPECT_DOUBLE_EQ(m.parts[1].hourglass_coefficient, 0.05);
  EXPECT_FALSE(m.controls.bulk_viscosity);
  EXPECT_DOUBLE_EQ(m.controls.bulk_q_linear, 0.1);
  EXPECT_TRUE(m.controls.bulk_linear_in_expansion);
  EXPECT_FALSE(read_scenario(scenario_path("bar_wave.yaml")).controls.bulk_linear_in_expansion);
  EXPECT_DOUBLE_EQ(m.controls.gravity_m_s2[2], -9.81);
  // Bilinear shorthand: H = E Et / (E - Et).
  const auto& h = m.materials[0].hardening;
  EXPECT_DOUBLE_EQ(h.yield(0.0), 2.0e8);
  EXPECT_NEAR(h.slope(0.01), 2e11 * 2e9 / (2e11 - 2e9), 1.0);
  int fixed = 0;
  for (auto f : m.fixed) {
    if (f != 0) {
      EXPECT_EQ(f, model::kUx | model::kRz);
    }
    fixed += f != 0 ? 1 : 0;
  }
  EXPECT_EQ(fixed, 18);
  ASSERT_EQ(m.initial_velocities.size(), 1u);
  EXPECT_EQ(m.initial_velocities[0].nodes.size(), 27u);  // b's nodes, shared face included
  ASSERT_EQ(m.loads.size(), 1u);
  EXPECT_EQ(m.loads[0].nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(m.loads[0].force.at(123.0), 3.5);
  EXPECT_EQ(m.probes[0].index, 0);
}

}  // namespace
}  // namespace crashlink::io
