// The `domains:` section: parts map onto model::Domain in file order; every part in exactly one
// domain; mistakes give file:line: key errors with the fix.
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
  hard: {type: rigid, density: 7850.0}
parts:
  plate:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, size: [1.0, 1.0], divisions: [2, 2]}
  frame:
    material: steel
    thickness: 0.001
    mesh: {generator: plate, origin: [1.0, 0.0, 0.0], size: [1.0, 1.0], divisions: [2, 2]}
  head:
    material: hard
    thickness: 0.002
    mesh: {generator: sphere, centre: [0.5, 0.5, 0.2], radius: 0.1, divisions: 2}
  neck:
    material: hard
    mesh: {generator: box, origin: [0.45, 0.45, 0.3], size: [0.1, 0.1, 0.1], divisions: [1, 1, 1]}
rigid_bodies:
  dummy: {parts: [head, neck]}
)";

int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

void expect_error(const std::string& domains, const std::string& marker, const std::string& key,
                  const std::string& fragment) {
  const std::string yaml = kScene + domains;
  try {
    (void)parse_scenario(yaml, "bad.yaml");
    ADD_FAILURE() << "accepted: " << domains;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line_of(yaml, marker)) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

TEST(ScenarioDomains, EachPartLandsInItsDomainInFileOrder) {
  const auto m = parse_scenario(kScene + R"(domains:
  body: {parts: [plate, frame]}
  impactor:
    parts: [neck, head]
)",
                                "ok.yaml");
  ASSERT_EQ(m.domains.size(), 2u);
  EXPECT_EQ(m.domains[0].name, "body");
  EXPECT_EQ(m.domains[0].parts, (std::vector<int>{0, 1}));
  EXPECT_EQ(m.domains[1].name, "impactor");
  EXPECT_EQ(m.domains[1].parts, (std::vector<int>{3, 2}));
}

TEST(ScenarioDomains, AbsentSectionMeansASingleDomainRun) {
  EXPECT_TRUE(parse_scenario(kScene, "ok.yaml").domains.empty());
}

TEST(ScenarioDomains, Mistakes) {
  expect_error(
      "domains:\n  a: {parts: [plate, frame, head, neck]}\n  b: {parts: [frame]}\n",
      "b: {parts: [frame]", "domains.b.parts[0]",
      "part 'frame' is already in domain 'a' (line 26); a part belongs to exactly one domain");
  expect_error("domains:\n  a: {parts: [plate]}\n", "domains:", "domains",
               "parts 'frame', 'head', 'neck' are in no domain; add each to exactly one domain");
  expect_error("domains:\n  a: {parts: [plate, frme, head, neck]}\n", "a: {parts",
               "domains.a.parts[1]", "unknown part 'frme'; did you mean 'frame'?");
  expect_error("domains:\n  a: {parts: [plate, frame, head, neck]}\n  b: {parts: []}\n",
               "b: {parts: []", "domains.b.parts", "lists no part; give at least one part name");
  expect_error("domains: {}\n", "domains:", "domains", "lists no domain");
  expect_error("domains:\n  a: {parts: [plate, frame, head, neck], step: 1}\n", "a: {parts",
               "domains.a.step", "unknown key");
  expect_error("domains:\n  a: {parts: [plate, frame, head]}\n  b: {parts: [neck]}\n",
               "b: {parts: [neck]", "domains.b.parts",
               "rigid body 'dummy' has part 'head' in domain 'a' and part 'neck' in domain 'b'");
}

TEST(ScenarioDomains, NamesThatCannotBeFileNamesAreRefusedAtTheirLine) {
  // Issue 20: `Wischer/ü` passed the reader and the run died in H5Fcreate ("internal error").
  const std::string rest = "  b: {parts: [plate, frame]}\n";
  auto domain = [&](const std::string& name) {
    return "domains:\n  " + name + ": {parts: [head, neck]}\n" + rest;
  };
  expect_error(domain("\"Wischer/\xc3\xbc\""), "Wischer", "domains.Wischer/\xc3\xbc",
               "domain name 'Wischer/\\xc3\\xbc' cannot be a file name (DIR/domains/<name>.h5, "
               "checkpoint folders): character 8, '/', is not allowed: a name that becomes a file "
               "name is 1 to 64 characters, each an ASCII letter, a digit, '_', '-' or '.', not "
               "starting with '.'; fix: rename it, e.g. 'Wischer__'");
  expect_error(domain("\"W\xc3\xbcscher\""), "scher", "domains.W\xc3\xbcscher",
               "character 2, a non-ASCII character (bytes \\xc3\\xbc), is not allowed");
  expect_error(domain("\".hidden\""), ".hidden", "domains..hidden", "it starts with '.'");
  expect_error(domain("\"..\""), "\"..\"", "domains...", "it starts with '.'");
  expect_error(domain("\"a b\""), "a b", "domains.a b", "character 2, ' ', is not allowed");
  expect_error(domain("\"a\\tb\""), "a\\tb", "domains.a\tb",
               "character 2, a control character (byte \\x09), is not allowed");
  expect_error(domain(std::string(65, 'x')), std::string(65, 'x'),
               "domains." + std::string(65, 'x'), "it has 65 characters, more than 64");
  expect_error(domain("coordinator"), "coordinator:", "domains.coordinator",
               "'coordinator' is the coordinator's own checkpoint folder");
  expect_error("domains:\n  car: {parts: [head, neck]}\n  Car: {parts: [plate, frame]}\n",
               "Car:", "domains.Car",
               "domain name 'Car' differs from 'car' (line 26) only in letter case");
  // What the rule allows.
  const auto m = parse_scenario(kScene + "domains:\n  Wischer_2-a.v1: {parts: [head, neck]}\n" +
                                    "  " + std::string(64, 'x') + ": {parts: [plate, frame]}\n",
                                "ok.yaml");
  ASSERT_EQ(m.domains.size(), 2u);
  EXPECT_EQ(m.domains[0].name, "Wischer_2-a.v1");
}

}  // namespace
}  // namespace crashlink::io
