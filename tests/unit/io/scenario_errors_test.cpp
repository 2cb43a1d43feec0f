// Every class of bad input gives an InputError "file:line: key: what; fix" at the right line.
// The expected line is found by searching the inline YAML for the offending text, so each test
// states the mistake once.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"
#include "solver/io/scenario_reader.h"
#include "tests/unit/io/yaml_marker.h"

namespace crashlink::io {
namespace {

using testing::line_of;

/// Parses `yaml` as "bad.yaml"; expects an InputError at the line of `marker`, for `key`, whose
/// message also contains `fragment`.
void expect_error(const std::string& yaml, const std::string& marker, const std::string& key,
                  const std::string& fragment) {
  const int line = line_of(yaml, marker);
  try {
    (void)parse_scenario(yaml, "bad.yaml");
    ADD_FAILURE() << "no error for mistake at '" << marker << "'";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.file(), "bad.yaml") << msg;
    EXPECT_EQ(e.line(), line) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find("bad.yaml:" + std::to_string(line) + ": " + key + ": "), std::string::npos)
        << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

// A valid scene every test breaks in one place.
const std::string kHead = R"(name: t
controls:
  end_time: 1.0e-3
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
)";

TEST(ScenarioErrors, ValidBaseParses) {
  const auto m = parse_scenario(kHead + R"(parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
)",
                                "ok.yaml");
  EXPECT_EQ(m.nodes.count(), 9u);
}

TEST(ScenarioErrors, MissingRequiredKey) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
)",
               "  plate:", "parts.plate.thickness", "required key missing; add 'thickness: ...'");
}

TEST(ScenarioErrors, MissingEndTime) {
  expect_error(R"(name: t
controls:
  dt_scale: 0.8
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
)",
               "controls:", "controls.end_time", "required key missing");
}

TEST(ScenarioErrors, StringWhereANumberIsExpected) {
  expect_error(R"(name: t
controls:
  end_time: 1.0e-3
materials:
  steel:
    type: elastic
    density: heavy
    youngs_modulus: 2.1e+11
    poisson_ratio: 0.3
)",
               "density: heavy", "materials.steel.density", "expected a number, got 'heavy'");
}

TEST(ScenarioErrors, NegativeThickness) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    thickness: -0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
)",
               "thickness: -0.001", "parts.plate.thickness", "must be > 0");
}

TEST(ScenarioErrors, ZeroDensity) {
  expect_error(R"(name: t
controls: {end_time: 1.0e-3}
materials:
  steel:
    type: rigid
    density: 0
)",
               "density: 0", "materials.steel.density", "must be > 0");
}

TEST(ScenarioErrors, ZeroDivisions) {
  expect_error(kHead + R"(parts:
  block:
    material: steel
    mesh:
      generator: box
      size: [1.0, 1.0, 1.0]
      divisions:
        - 2
        - 0
        - 2
)",
               "- 0", "parts.block.mesh.divisions[1]", "integer >= 1");
}

TEST(ScenarioErrors, NegativeSize) {
  expect_error(kHead + R"(parts:
  block:
    material: steel
    mesh: {generator: box, size: [1.0, -1.0, 1.0], divisions: [1, 1, 1]}
)",
               "mesh:", "parts.block.mesh.size[1]", "must be > 0");
}

TEST(ScenarioErrors, TypoInKeySuggestsTheNearest) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    thicknes: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
)",
               "thicknes:", "parts.plate.thicknes", "did you mean 'thickness'?");
}

TEST(ScenarioErrors, TypoInTopLevelSection) {
  expect_error(kHead + R"(part:
  plate: {material: steel}
)",
               "part:", "part", "did you mean 'parts'?");
}

TEST(ScenarioErrors, UnknownMaterialReferenced) {
  expect_error(kHead + R"(parts:
  plate:
    material: steal
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
)",
               "material: steal", "parts.plate.material",
               "unknown material 'steal'; did you mean 'steel'?");
}

TEST(ScenarioErrors, UnknownGenerator) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    thickness: 0.001
    mesh:
      generator: plane
      size: [1.0, 1.0]
)",
               "generator: plane", "parts.plate.mesh.generator", "did you mean 'plate'?");
}

TEST(ScenarioErrors, UnknownNodeSetReferenced) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
node_sets:
  edge: {part: plate, box: {min: [0, 0, 0], max: [0, 1, 0]}}
boundary:
  - nodes: edg
    fix: all
)",
               "nodes: edg", "boundary[0].nodes", "unknown node set 'edg'; did you mean 'edge'?");
}

TEST(ScenarioErrors, EmptySelection) {
  expect_error(kHead + R"(parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
node_sets:
  edge:
    part: plate
    box: {min: [2, 0, 0], max: [3, 1, 0]}
)",
               "box:", "node_sets.edge.box", "selects no node");
}

TEST(ScenarioErrors, UnknownPartInRigidBody) {
  expect_error(R"(name: t
controls: {end_time: 1.0e-3}
materials:
  rig: {type: rigid, density: 7850.0}
parts:
  ball:
    material: rig
    thickness: 0.001
    mesh: {generator: sphere, centre: [0, 0, 0], radius: 0.1, divisions: 2}
rigid_bodies:
  head:
    parts:
      - bal
)",
               "- bal", "rigid_bodies.head.parts[0]", "unknown part 'bal'; did you mean 'ball'?");
}

// rigid_walls and a body's motion: each mistake at its line, with the fix.
TEST(ScenarioErrors, RigidWallsAndBodyMotions) {
  const std::string scene = kHead + R"(  rig: {type: rigid, density: 7850.0}
parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
  ram:
    material: rig
    thickness: 0.001
    mesh: {generator: plate, origin: [0, 0, 0.1], size: [1.0, 1.0], divisions: [1, 1]}
rigid_bodies:
  ram: {parts: [ram], fix: [x, y]}
)";
  expect_error(scene + R"(rigid_walls:
  floor: {nodes: {part: plate}, point: [0, 0, 0], normal: [0, 0, 1], velocity: 2.0}
)",
               "velocity: 2.0", "rigid_walls.floor.velocity", "needs its `mass`");
  expect_error(scene + R"(rigid_walls:
  roller: {nodes: {part: plate}, shape: cylinder, point: [0, 0, 0], normal: [0, 0, 1]}
)",
               "roller:", "rigid_walls.roller.normal", "does not belong to a cylinder");
  expect_error(scene + R"(rigid_walls:
  pad: {nodes: {part: plate}, point: [0, 0, 0], normal: [0, 0, 1], edge: [0, 1, 1], length: 1.0, width: 1.0}
)",
               "pad:", "rigid_walls.pad.edge", "is not in the wall's plane");
  expect_error(scene + R"(rigid_walls:
  floor: {nodes: {part: plate}, point: [0, 0, 0], normal: [0, 0, 0]}
)",
               "floor:", "rigid_walls.floor.normal", "is the zero vector");
  expect_error(scene + R"(prescribed_velocity:
  - {rigid_body: rom, dof: z, value: 1.0}
)",
               "rigid_body: rom", "prescribed_velocity[0].rigid_body", "no rigid body 'rom'");
  expect_error(scene + R"(prescribed_velocity:
  - {rigid_body: ram, nodes: {part: plate}, dof: z, value: 1.0}
)",
               "rigid_body: ram", "prescribed_velocity[0].rigid_body", "not both");
}

TEST(ScenarioErrors, RigidPartWithoutBody) {
  expect_error(R"(name: t
controls: {end_time: 1.0e-3}
materials:
  rig: {type: rigid, density: 7850.0}
parts:
  ball:
    material: rig
    thickness: 0.001
    mesh: {generator: sphere, centre: [0, 0, 0], radius: 0.1, divisions: 2}
)",
               "ball:", "parts.ball", "belongs to no rigid body");
}

TEST(ScenarioErrors, CurveTimesNotIncreasing) {
  expect_error(kHead + R"(parts:
  bar:
    material: steel
    mesh: {generator: bar, length: 1.0, cross_section: [0.01, 0.01], divisions: 4}
node_sets:
  end: {part: bar, box: {min: [0, -1, -1], max: [0, 1, 1]}}
prescribed_velocity:
  - nodes: end
    dof: x
    curve:
      t: [0.0, 2.0e-5, 1.0e-5]
      v: [0.0, 1.0, 0.0]
)",
               "t: [0.0", "prescribed_velocity[0].curve.t", "must increase strictly");
}

TEST(ScenarioErrors, WrongElementForGenerator) {
  expect_error(kHead + R"(parts:
  ball:
    material: steel
    element: hex8
    mesh: {generator: sphere, centre: [0, 0, 0], radius: 0.1, divisions: 2}
)",
               "element: hex8", "parts.ball.element", "use element: shell4");
}

TEST(ScenarioErrors, ProbeAtMissingNodeId) {
  expect_error(kHead + R"(parts:
  bar:
    material: steel
    mesh: {generator: bar, length: 1.0, cross_section: [0.01, 0.01], divisions: 4}
probes:
  p: {node: 999}
)",
               "p: {node", "probes.p.node", "node id 999 is not in the model");
}

TEST(ScenarioErrors, YamlSyntaxError) {
  expect_error(R"(name: t
controls:
  end_time: [1.0e-3
materials: {}
)",
               "materials", "(yaml syntax)", "check the indentation");
}

TEST(ScenarioErrors, MissingFileNamesIt) {
  try {
    (void)read_scenario("/nonexistent/dir/scene.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.yaml"), std::string::npos);
  }
}

// A typo in divisions must fail at its line, not exhaust memory (fuzz regression,
// docs/fuzzing.md).
TEST(ScenarioErrors, TooManyElements) {
  expect_error(kHead + R"(parts:
  sheet:
    material: steel
    thickness: 1.0e-3
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [100000, 100000]}
)",
               "mesh:", "parts.sheet.mesh.divisions", "more than the 1000000");
}

}  // namespace
}  // namespace crashlink::io
