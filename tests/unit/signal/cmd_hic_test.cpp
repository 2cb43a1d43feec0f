// `crashlink hic` end to end on CSV files (docs/design.md §4): runs the built binary
// CRASHLINK_BINARY_DIR/apps/crashlink and reads its output and exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

const std::string kCrashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CommandRun run(const std::string& args) {
  CommandRun r;
  const std::string cmd = "'" + kCrashlink + "' " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) r.output += buf.data();
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string temp_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_cmd_hic_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// HICnn value and window from the output; nan if absent.
struct Hic {
  double value = NAN, t1_ms = NAN, t2_ms = NAN;
};
Hic parse_hic(const std::string& out, int window) {
  const std::regex re("HIC" + std::to_string(window) +
                      R"( = ([0-9.]+) \(t1 = ([0-9.]+) ms, t2 = ([0-9.]+) ms\))");
  std::smatch m;
  Hic h;
  if (std::regex_search(out, m, re)) {
    h.value = std::stod(m[1]);
    h.t1_ms = std::stod(m[2]);
    h.t2_ms = std::stod(m[3]);
  }
  return h;
}

class CmdHic : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(kCrashlink))
        << kCrashlink << " is not built: build the crashlink target before the tests";
  }
};

TEST_F(CmdHic, RectangularPulseCsv) {
  // 100 g from 5 to 15 ms, 10 kHz, 30 ms: HIC15 = HIC36 = 1000 on [5, 15] ms.
  const std::string path = temp_file("rect.csv");
  {
    std::ofstream f(path);
    f << "time_s,accel_g\n";
    for (int k = 0; k <= 300; ++k)
      f << k * 1e-4 << "," << ((k >= 50 && k <= 150) ? 100 : 0) << "\n";
  }
  const CommandRun r = run("hic " + path);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::printf("%s", r.output.c_str());
  for (int w : {15, 36}) {
    const Hic h = parse_hic(r.output, w);
    EXPECT_NEAR(h.value, 1000.0, 1.0) << r.output;
    EXPECT_NEAR(h.t1_ms, 5.0, 1e-3);
    EXPECT_NEAR(h.t2_ms, 15.0, 1e-3);
  }
  EXPECT_NE(r.output.find("filter: none"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("peak acceleration = 100 g at 5.000 ms"), std::string::npos) << r.output;

  const CommandRun w = run("hic " + path + " --window 36 --cfc 1000");
  ASSERT_EQ(w.exit_code, 0) << w.output;
  EXPECT_TRUE(std::isnan(parse_hic(w.output, 15).value)) << w.output;
  EXPECT_GT(parse_hic(w.output, 36).value, 900.0) << w.output;
  EXPECT_NE(w.output.find("filter: CFC 1000"), std::string::npos) << w.output;
}

TEST_F(CmdHic, BadInputFailsWithAClearMessage) {
  const CommandRun missing = run("hic " + temp_file("does_not_exist.csv"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("no such file"), std::string::npos) << missing.output;

  const std::string header = temp_file("header.csv");
  std::ofstream(header) << "time,accel\n0,1\n0.001,2\n";
  const CommandRun h = run("hic " + header);
  EXPECT_EQ(h.exit_code, 2) << h.output;
  EXPECT_NE(h.output.find("the first line must be the header 'time_s,accel_g'"), std::string::npos)
      << h.output;

  const std::string order = temp_file("order.csv");
  std::ofstream(order) << "time_s,accel_g\n0,1\n0.002,2\n0.002,3\n";
  const CommandRun o = run("hic " + order);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(":4: time_s: time 0.002 s does not increase"), std::string::npos)
      << o.output;

  const CommandRun probe = run("hic " + order + " --probe head");
  EXPECT_EQ(probe.exit_code, 2) << probe.output;
  EXPECT_NE(probe.output.find("--probe head applies to result.h5"), std::string::npos)
      << probe.output;

  const CommandRun cfc = run("hic " + order + " --cfc 100");
  EXPECT_NE(cfc.exit_code, 0) << cfc.output;
}

}  // namespace
