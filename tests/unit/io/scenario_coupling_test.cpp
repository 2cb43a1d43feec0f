// The top-level key `coupling` (docs/scenario-format.md "coupling"): interface damping of the
// layer scheme read into Model::coupling; mistakes are InputErrors at their own line with the fix.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::io {
namespace {

const std::string kScene = R"(name: t
controls:
  end_time: 1.0e-3
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
  frame:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, origin: [1.0, 0.0, 0.0], size: [1.0, 1.0], divisions: [2, 2]}
)";
const std::string kDomains = "domains:\n  a: {parts: [plate]}\n  b: {parts: [frame]}\n";

int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

void expect_error(const std::string& yaml, const std::string& marker, const std::string& key,
                  const std::string& fragment) {
  try {
    (void)parse_scenario(yaml, "bad.yaml");
    ADD_FAILURE() << "accepted: " << yaml;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line_of(yaml, marker)) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

TEST(ScenarioCoupling, InterfaceDampingIsRead) {
  const auto m0 = parse_scenario(kScene + kDomains, "ok.yaml");
  EXPECT_EQ(m0.coupling.interface_damping.ratio, 0.0);  // off by default
  const auto m = parse_scenario(
      kScene + kDomains + "coupling:\n  interface_damping: {ratio: 0.06, layers: 2}\n", "ok.yaml");
  EXPECT_DOUBLE_EQ(m.coupling.interface_damping.ratio, 0.06);
  EXPECT_EQ(m.coupling.interface_damping.layers, 2);
  const auto m3 = parse_scenario(
      kScene + kDomains + "coupling:\n  interface_damping: {ratio: 0.05}\n", "ok.yaml");
  EXPECT_EQ(m3.coupling.interface_damping.layers, 3);  // default
}

TEST(ScenarioCoupling, MistakesAreErrorsAtTheirLine) {
  const std::string base = kScene + kDomains;
  expect_error(base + "coupling:\n  interface_damping: {ratio: 0.7}\n", "interface_damping",
               "coupling.interface_damping.ratio", "0.7 exceeds 0.5");
  expect_error(base + "coupling:\n  interface_damping: {ratio: -0.1}\n", "interface_damping",
               "coupling.interface_damping.ratio", ">= 0");
  expect_error(base + "coupling:\n  interface_damping: {ratio: 0.06, layers: 0}\n",
               "interface_damping", "coupling.interface_damping.layers", "0");
  expect_error(base + "coupling:\n  interface_damping: {layers: 2}\n", "interface_damping",
               "coupling.interface_damping.ratio", "required key missing");
  expect_error(base + "coupling:\n  interface_damping: {ratio: 0.06, layer: 2}\n",
               "interface_damping", "coupling.interface_damping.layer", "did you mean 'layers'");
  expect_error(base + "coupling:\n  damping: 0.06\n", "damping:", "coupling.damping",
               "valid keys here: 'interface_damping'");
  expect_error(kScene + "coupling:\n  interface_damping: {ratio: 0.06}\n", "coupling:", "coupling",
               "without a `domains` section");
}

}  // namespace
}  // namespace crashlink::io
