// `crashlink stability-map` end to end on a short map (the README's command runs 10^5 fine steps):
// exit 0, one CSV row per shape x configuration x ratio with finite values, the PNG written;
// `paper` runs the bar (at r = 1 as mono does) and refuses the plate's shell links. The physics of
// the map is asserted by LayerStability.* (layer_stability_test.cpp) and PaperScheme.*.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

TEST(StabilityMap, ShortMapWritesFiniteCsvAndPng) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_stability_map_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  std::filesystem::remove_all(dir);
  int status = -1;
  const std::string out = crashlink::testing::run_command(
      std::string(CRASHLINK_BINARY_DIR) +
          "/apps/crashlink stability-map --steps 1500 --ratios 1,2.5 --shapes bar,plate,contact "
          "--penalties 0.1 --out " +
          dir.string(),
      status);
  ASSERT_EQ(status, 0) << out;
  ASSERT_GT(std::filesystem::file_size(dir / "stability_map.png"), 1000u);
  std::ifstream f(dir / "stability_map.csv");
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line.rfind("shape,configuration,ratio", 0), 0u) << line;
  int rows = 0, paper_rows = 0, contact_rows = 0, lts_rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cell.push_back(c);
    ASSERT_GE(cell.size(), 9u) << line;
    for (std::size_t k = 2; k < 9; ++k) {
      const double v = std::stod(cell[k]);
      EXPECT_TRUE(std::isfinite(v)) << line;
    }
    const bool stopped = cell.size() > 9 && !cell[9].empty();
    if (cell[0] == "contact") {
      ++contact_rows;
      // layer: r = 1 has no finer side to move the slab's surface into (the cut refuses it, said
      // in the row), r = 2.5 runs; paper: may be stopped by its own guard, never refused, and no
      // longer by a contact creating energy (issue 21; before: 'block_on_slab' created 0.072 J,
      // 6.95 % of E0, at r = 1 with [11]; measured since: both ratios run the 1500 steps).
      if (cell[1].rfind("layer", 0) == 0) {
        EXPECT_EQ(stopped, std::stod(cell[2]) == 1.0) << line;
      } else {
        EXPECT_TRUE(!stopped || line.find("went unstable") != std::string::npos) << line;
        EXPECT_EQ(line.find("created by contacts"), std::string::npos) << line;
      }
      continue;
    }
    if (cell[1] == "lts") ++lts_rows;
    if (cell[1].rfind("paper", 0) != 0) {
      EXPECT_FALSE(stopped) << "layer, short run: " << line;
      EXPECT_LT(std::stod(cell[5]), 0.2) << "max rise, short run: " << line;
      continue;
    }
    ++paper_rows;
    if (cell[0] == "plate") {  // shell links carry rotations: the paper runner refuses them
      EXPECT_TRUE(stopped && line.find("rotations") != std::string::npos) << line;
    } else if (std::stod(cell[2]) == 1.0) {  // r = 1: the paper scheme is mono's integration
      EXPECT_FALSE(stopped) << line;
      EXPECT_LT(std::stod(cell[5]), 1e-3) << line;
    }
  }
  // linked: bar 10 configurations, plate 7 (no uniaxial variant), x ratios; + contact
  EXPECT_EQ(rows, (10 + 7) * 2 + 2 * 2);
  EXPECT_EQ(lts_rows, 2 * 2);
  EXPECT_EQ(paper_rows, (7 + 4) * 2);
  EXPECT_EQ(contact_rows, 2 * 2);  // (layer, paper) x ratios at one penalty
}
