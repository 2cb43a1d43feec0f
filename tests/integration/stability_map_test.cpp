// `crashlink stability-map` end to end on a short map (the README's command runs 10^5 fine steps):
// exit 0, one CSV row per shape x configuration x ratio with finite values, the PNG written. The
// physics of the map is asserted by LayerStability.* (layer_stability_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/integration/shell_command.h"

TEST(StabilityMap, ShortMapWritesFiniteCsvAndPng) {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_stability_map";
  std::filesystem::remove_all(dir);
  int status = -1;
  const std::string out = crashlink::testing::run_command(
      std::string(CRASHLINK_BINARY_DIR) +
          "/apps/crashlink stability-map --steps 1500 --ratios 1,2.5 --shapes bar,plate --out " +
          dir.string(),
      status);
  ASSERT_EQ(status, 0) << out;
  ASSERT_GT(std::filesystem::file_size(dir / "stability_map.png"), 1000u);
  std::ifstream f(dir / "stability_map.csv");
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line.rfind("shape,configuration,ratio", 0), 0u) << line;
  int rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cell.push_back(c);
    ASSERT_GE(cell.size(), 8u) << line;
    for (std::size_t k = 2; k < 8; ++k) {
      const double v = std::stod(cell[k]);
      EXPECT_TRUE(std::isfinite(v)) << line;
    }
    EXPECT_LT(std::stod(cell[5]), 0.2) << "max rise, short run: " << line;
  }
  EXPECT_EQ(rows, 2 * 2 * 2);  // shapes x configurations x ratios
}
