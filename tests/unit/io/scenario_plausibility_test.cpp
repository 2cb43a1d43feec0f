// Plausibility checks (docs/scenario-format.md "Plausibility checks", issue 20 item 9): values
// valid one by one but implausible for their neighbours, the usual unit mistakes, are refused at
// their line with the fix; controls.plausibility_checks: false lets them through.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/errors.h"
#include "solver/io/scenario_reader.h"
#include "tests/unit/io/yaml_marker.h"

namespace crashlink::io {
namespace {

using testing::line_of;

void expect_refused(const std::string& yaml, const std::string& marker, const std::string& key,
                    const std::string& fix) {
  const int line = line_of(yaml, marker);
  try {
    (void)parse_scenario(yaml, "units.yaml");
    ADD_FAILURE() << "no error for the implausible '" << marker << "'";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find("units.yaml:" + std::to_string(line) + ": " + key + ": "), std::string::npos)
        << msg;
    EXPECT_NE(msg.find(fix), std::string::npos) << msg;
    EXPECT_NE(msg.find("plausibility_checks: false"), std::string::npos) << msg;
  }
}

/// A 0.2 x 0.2 m steel plate of 10 mm shells, 1 ms; `controls_extra`, `thickness`, `E`, `rho`,
/// `probe` replace one value each.
std::string scene(const std::string& thickness = "0.0007", const std::string& E = "2.1e+11",
                  const std::string& rho = "7850.0", const std::string& probe = "[0.1, 0.1, 0.0]",
                  const std::string& end = "1.0e-3", const std::string& controls_extra = "") {
  return "name: t\ncontrols:\n  end_time: " + end +
         "\n  history_interval: 0.0\n  field_interval: 1.0e-4\n" + controls_extra +
         "materials:\n  steel: {type: elastic, density: " + rho + ", youngs_modulus: " + E +
         ", poisson_ratio: 0.3}\nparts:\n  plate:\n    material: steel\n    thickness: " +
         thickness +
         "\n    mesh: {generator: plate, size: [0.2, 0.2], divisions: [20, 20]}\nprobes:\n  "
         "centre: {node_near: " +
         probe + "}\n";
}

TEST(ScenarioPlausibility, TheBaseSceneParses) {
  const auto m = parse_scenario(scene(), "units.yaml");
  EXPECT_EQ(m.element_count(), 400u);
}

TEST(ScenarioPlausibility, ShellThicknessInMm) {
  expect_refused(scene("0.7"), "thickness: 0.7", "parts.plate.thickness",
                 "did you mean mm? write 0.0007 m");
}

TEST(ScenarioPlausibility, ModulusInGPa) {
  expect_refused(scene("0.0007", "210"), "youngs_modulus: 210", "materials.steel.youngs_modulus",
                 "youngs_modulus in GPa? write 2.1e+11 Pa");
}

TEST(ScenarioPlausibility, DensityInGramsPerCm3) {
  expect_refused(scene("0.0007", "2.1e+11", "7.85"), "youngs_modulus: 2.1e+11",
                 "materials.steel.youngs_modulus", "density in g/cm^3? write 7850 kg/m^3");
}

TEST(ScenarioPlausibility, ProbeInMm) {
  expect_refused(scene("0.0007", "2.1e+11", "7850.0", "[100.0, 100.0, 0.0]"),
                 "node_near:", "probes.centre.node_near", "did you mean mm? write [0.1, 0.1, 0]");
}

TEST(ScenarioPlausibility, EndTimeInMs) {
  expect_refused(scene("0.0007", "2.1e+11", "7850.0", "[0.1, 0.1, 0.0]", "8"), "end_time: 8",
                 "controls.end_time", "did you mean ms? write 0.008 s");
}

TEST(ScenarioPlausibility, TheOverrideLetsThemThrough) {
  const auto m = parse_scenario(
      scene("0.7", "210", "7850.0", "[100.0, 100.0, 0.0]", "8", "  plausibility_checks: false\n"),
      "units.yaml");
  EXPECT_DOUBLE_EQ(m.parts[0].thickness_m, 0.7);
  EXPECT_DOUBLE_EQ(m.materials[0].youngs_modulus_Pa, 210.0);
}

TEST(ScenarioPlausibility, SoftButPlausibleMaterialsPass) {
  // Aluminium, a polymer (E 2 GPa, 1200 kg/m^3: 1290 m/s), a stiff foam (E 20 MPa, 100 kg/m^3:
  // 447 m/s).
  for (const auto& [E, rho] : {std::pair<std::string, std::string>{"7.0e+10", "2700.0"},
                               {"2.0e+9", "1200.0"},
                               {"2.0e+7", "100.0"}})
    EXPECT_NO_THROW((void)parse_scenario(scene("0.0007", E, rho), "units.yaml")) << E;
}

}  // namespace
}  // namespace crashlink::io

namespace crashlink::io {
namespace {

// No shipped scenario trips a check (scenarios/, bench/scenarios/): they are all read as they
// are, checks on.
TEST(ScenarioPlausibility, EveryShippedScenarioPasses) {
  int count = 0;
  for (const char* dir : {"scenarios", "bench/scenarios"})
    for (const auto& f :
         std::filesystem::directory_iterator(std::filesystem::path(CRASHLINK_SOURCE_DIR) / dir)) {
      if (f.path().extension() != ".yaml") continue;
      EXPECT_NO_THROW((void)read_scenario(f.path().string())) << f.path();
      ++count;
    }
  EXPECT_GE(count, 7);
}

}  // namespace
}  // namespace crashlink::io
