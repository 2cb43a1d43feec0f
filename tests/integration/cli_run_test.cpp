// `crashlink run` end to end on the CI variant of the main job: exit 0, the summary, a readable
// result.h5 with the contact history, and HIC15/HIC36 printed for the headform probe.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "solver/io/result_reader.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

using crashlink::testing::run_command;

TEST(CliRun, HeadformOnPlatePrintsSummaryAndHic) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("crashlink_cli_run_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
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

// The start of a run prints what it will cost (model/run_estimate.h) on stderr: cycles, CPU and
// output, so that a mistake in the units shows before hours are spent.
TEST(CliRun, TheStartPrintsTheEstimate) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_cli_estimate_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  std::filesystem::remove_all(dir);
  int status = -1;
  const std::string out =
      run_command(std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " +
                      CRASHLINK_SOURCE_DIR + "/scenarios/bar_wave.yaml --out " + dir.string(),
                  status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("model: estimated ~"), std::string::npos) << out;
  EXPECT_NE(out.find(" cycles at dt ~"), std::string::npos) << out;
  EXPECT_NE(out.find("of output"), std::string::npos) << out;
}

// A unit mistake the reader refuses (docs/scenario-format.md "Plausibility checks") ends the run
// before it starts with exit code 2, file:line and the fix.
TEST(CliRun, AShellThicknessInMmIsRefusedWithExitCode2) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_cli_units_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string yaml;
  {
    std::ifstream in(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/plate_impact_small.yaml");
    yaml.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = yaml.find("thickness: 7.0e-4");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, 17, "thickness: 0.7   ");
  const auto file = dir / "thick.yaml";
  std::ofstream(file) << yaml;
  int status = -1;
  const std::string out = run_command(std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " +
                                          file.string() + " --out " + (dir / "out").string(),
                                      status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("thick.yaml:30: parts.plate.thickness: 0.7 m is above"), std::string::npos)
      << out;
  EXPECT_NE(out.find("did you mean mm? write 0.0007 m"), std::string::npos) << out;
}
