#include "solver/io/scenario_hash.h"

#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"

namespace crashlink::io {
namespace {

TEST(ScenarioHash, Fnv1aReferenceValues) {
  // Published FNV-1a 64 test vectors.
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ULL);
}

TEST(ScenarioHash, IgnoresLayoutAndCommentsNotContent) {
  const std::string a = "name: x\ncontrols:\n  end_time: 0.01\nlist: [1, 2]\n";
  const std::string b =
      "# a comment\nname: x   # trailing\ncontrols: {end_time: 0.01}\nlist:\n  - 1\n  - 2\n";
  const std::string c = "name: x\ncontrols:\n  end_time: 0.02\nlist: [1, 2]\n";
  const std::string h = scenario_hash_of_text(a);
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, scenario_hash_of_text(b));
  EXPECT_NE(h, scenario_hash_of_text(c));
  EXPECT_EQ(h, scenario_hash_of_text(a));  // stable
}

TEST(ScenarioHash, FileAndTextAgree) {
  const std::string path = std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/bar_wave.yaml";
  EXPECT_EQ(scenario_hash(path).size(), 16u);
  EXPECT_THROW(scenario_hash("/nonexistent.yaml"), InputError);
  EXPECT_THROW(scenario_hash_of_text("a: [1, 2"), InputError);
}

}  // namespace
}  // namespace crashlink::io
