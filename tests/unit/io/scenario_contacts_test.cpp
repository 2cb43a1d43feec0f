// The `contacts:` section: values map onto model::Contact; mistakes give file:line: key errors.
#include <gtest/gtest.h>

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
  block:
    material: steel
    mesh: {generator: box, origin: [0.2, 0.2, 0.01], size: [0.1, 0.1, 0.1], divisions: [1, 1, 1]}
)";

TEST(ScenarioContacts, ValuesMapOntoTheModel) {
  const auto m = parse_scenario(kScene + R"(contacts:
  block_on_plate:
    slave: {part: block}
    master: plate
    penalty_scale: 0.2
    soft: {enabled: true, scale: 0.3}
    friction: {static: 0.3, dynamic: 0.2, decay: 5.0}
)",
                                "ok.yaml");
  ASSERT_EQ(m.contacts.size(), 1u);
  const auto& c = m.contacts[0];
  EXPECT_EQ(c.name, "block_on_plate");
  EXPECT_EQ(c.slave_nodes.size(), 8u);  // the hex's nodes
  ASSERT_EQ(c.master_parts.size(), 1u);
  EXPECT_EQ(m.parts[static_cast<std::size_t>(c.master_parts[0])].name, "plate");
  EXPECT_DOUBLE_EQ(c.penalty_scale, 0.2);
  EXPECT_TRUE(c.soft);
  EXPECT_DOUBLE_EQ(c.soft_scale, 0.3);
  EXPECT_DOUBLE_EQ(c.static_friction, 0.3);
  EXPECT_DOUBLE_EQ(c.dynamic_friction, 0.2);
  EXPECT_DOUBLE_EQ(c.friction_decay_s_m, 5.0);
}

TEST(ScenarioContacts, TypeSelectsThePassesAndDefaultsToTwoPassWithSoftStiffness) {
  const auto m = parse_scenario(kScene + R"(contacts:
  two:
    slave: {part: block}
    master: plate
  one:
    type: node_to_surface
    slave: {part: block}
    master: plate
  self:
    type: single_surface
    master: [plate]
)",
                                "ok.yaml");
  ASSERT_EQ(m.contacts.size(), 3u);
  EXPECT_EQ(m.contacts[0].kind, model::ContactKind::SurfaceToSurface);
  EXPECT_TRUE(m.contacts[0].soft);
  EXPECT_EQ(m.contacts[1].kind, model::ContactKind::NodeToSurface);
  EXPECT_EQ(m.contacts[2].kind, model::ContactKind::SingleSurface);
  EXPECT_TRUE(m.contacts[2].slave_nodes.empty());
  // the unknown type on its line (16); a slave given to a single-surface contact on its own (17)
  const std::pair<const char*, int> bad[] = {
      {"    type: two_pass\n    slave: {part: block}\n    master: plate\n", 16},
      {"    type: single_surface\n    slave: {part: block}\n    master: plate\n", 17}};
  for (const auto& [text, line] : bad) {
    try {
      (void)parse_scenario(kScene + "contacts:\n  c:\n" + text, "bad.yaml");
      FAIL() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
    }
  }
}

TEST(ScenarioContacts, UnknownMasterPartNamesTheLineAndSuggests) {
  try {
    (void)parse_scenario(kScene + R"(contacts:
  c:
    slave: {part: block}
    master: plat
)",
                         "bad.yaml");
    FAIL() << "accepted an unknown master part";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), 17) << msg;
    EXPECT_NE(msg.find("contacts.c.master"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'plate'"), std::string::npos) << msg;
  }
}

TEST(ScenarioContacts, DynamicAboveStaticFrictionIsRefused) {
  EXPECT_THROW((void)parse_scenario(kScene + R"(contacts:
  c:
    slave: {part: block}
    master: plate
    friction: {static: 0.1, dynamic: 0.3}
)",
                                    "bad.yaml"),
               InputError);
}

}  // namespace
}  // namespace crashlink::io
