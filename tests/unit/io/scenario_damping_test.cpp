// The part key `damping_ratio` (docs/scenario-format.md, parts): read into Part::damping_ratio;
// out of range, negative or on a rigid part it is an InputError at its own line with the fix.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::io {
namespace {

int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

void expect_error(const std::string& yaml, const std::string& marker, const std::string& fragment) {
  try {
    (void)parse_scenario(yaml, "bad.yaml");
    ADD_FAILURE() << "no error for '" << marker << "'";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line_of(yaml, marker)) << msg;
    EXPECT_EQ(e.key(), "parts.plate.damping_ratio") << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

const std::string kHead = R"(name: t
controls:
  end_time: 1.0e-3
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
  rig: {type: rigid, density: 7850.0}
parts:
  plate:
)";

std::string plate(const std::string& material, const std::string& ratio) {
  return kHead + "    material: " + material + "\n    thickness: 0.001\n" +
         "    damping_ratio: " + ratio + "\n" +
         "    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}\n";
}

TEST(ScenarioDamping, RatioIsRead) {
  const auto m = parse_scenario(plate("steel", "0.05"), "ok.yaml");
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_DOUBLE_EQ(m.parts[0].damping_ratio, 0.05);
  EXPECT_TRUE(m.parts[0].element_damping_ratio.empty());
  const auto m0 = parse_scenario(plate("steel", "0"), "ok.yaml");
  EXPECT_EQ(m0.parts[0].damping_ratio, 0.0);
  EXPECT_FALSE(m0.parts[0].damped());
}

TEST(ScenarioDamping, BadRatiosAreErrorsAtTheirLine) {
  expect_error(plate("steel", "0.7"), "damping_ratio", "0.7 is above 0.5");
  expect_error(plate("steel", "-0.1"), "damping_ratio", "must be >= 0");
  expect_error(plate("steel", "lots"), "damping_ratio", "lots");
}

TEST(ScenarioDamping, RigidPartIsAnError) {
  const std::string yaml = plate("rig", "0.05") + "rigid_bodies:\n  head: {parts: [plate]}\n";
  expect_error(yaml, "damping_ratio", "has no effect on a part of rigid material 'rig'");
}

}  // namespace
}  // namespace crashlink::io
