// `crashlink run` end to end on the CI variant of the main job: exit 0, the summary, a readable
// result.h5 with the contact history, and HIC15/HIC36 printed for the headform probe.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "solver/io/result_reader.h"
#include "tests/integration/shell_command.h"

using crashlink::testing::run_command;

TEST(CliRun, HeadformOnPlatePrintsSummaryAndHic) {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_cli_run";
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " +
                          CRASHLINK_SOURCE_DIR +
                          "/scenarios/plate_impact_small.yaml --quiet --out " + dir.string();
  int status = -1;
  const std::string out = run_command(cmd, status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("energy balance error"), std::string::npos) << out;
  EXPECT_NE(out.find("HIC15 = "), std::string::npos) << out;
  EXPECT_NE(out.find("HIC36 = "), std::string::npos) << out;
  crashlink::io::ResultReader r((dir / "result.h5").string());
  const auto head = r.probe("headform");
  ASSERT_GT(head.time_s.size(), 100u);
  // The headform is stopped by the plate: its z-velocity rises from -9.72 m/s.
  EXPECT_GT(head.velocity_m_s[3 * (head.time_s.size() - 1) + 2], -9.0);
}

TEST(CliRun, UnknownModeIsRefusedWithExitCode2) {
  int status = -1;
  const std::string out =
      run_command(std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " +
                      CRASHLINK_SOURCE_DIR + "/scenarios/plate_impact_small.yaml --mode multi",
                  status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("--mode multi"), std::string::npos) << out;
}
