// The result reader: probe histories and glstat written by ResultWriter read back exactly, probe
// lookup by user and link name, errors; and `crashlink hic FILE.h5 --probe NAME` end to end.
#include "solver/io/result_reader.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <regex>
#include <string>

#include "core/errors.h"
#include "solver/io/result_writer.h"
#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

using test::fresh_dir;
using test::small_model;

GlstatSample glstat_row(int i) {
  const double t = 1e-4 * i;
  return GlstatSample{t, 1.0 + i, 2.0 + i, 0.1 * i, 0.01 * i, 3.0 * i, 1.0 + 2.0 * i, 1e-6 * i};
}

/// Probe j of row i: distinct values per probe, component and row.
std::vector<ProbeSample> probe_rows(int i, std::size_t probes) {
  std::vector<ProbeSample> p(probes);
  for (std::size_t j = 0; j < probes; ++j) {
    for (int c = 0; c < 3; ++c) {
      p[j].displacement_m[c] = 0.001 * i + c + 10.0 * static_cast<double>(j);
      p[j].velocity_m_s[c] = -0.5 * i + c + 10.0 * static_cast<double>(j);
      p[j].acceleration_m_s2[c] = 9.81 * i - c + 10.0 * static_cast<double>(j);
    }
  }
  return p;
}

void write_rows(ResultWriter& w, int rows, std::size_t probes) {
  for (int i = 0; i < rows; ++i) w.append_history(glstat_row(i), probe_rows(i, probes));
}

TEST(ResultReader, RoundTripOfProbesAndGlstat) {
  const auto m = small_model();  // probes "tip" (node) and "head" (rigid body)
  const std::string dir = fresh_dir("out");
  {
    ResultWriter w(dir, m, ResultWriterOptions{1000, 1e9, 256});
    write_rows(w, 2500, m.probes.size());
  }
  const ResultReader r(dir + "/result.h5");
  EXPECT_EQ(r.model_name(), "tiny");
  EXPECT_EQ(r.probe_names(), (std::vector<std::string>{"head", "tip"}));  // link (name) order
  EXPECT_TRUE(r.has_probe("tip"));
  EXPECT_FALSE(r.has_probe("toe"));
  for (std::size_t j = 0; j < m.probes.size(); ++j) {
    const ProbeHistory p = r.probe(m.probes[j].name);
    EXPECT_EQ(p.name, m.probes[j].name);
    EXPECT_EQ(p.kind, j == 0 ? "node" : "rigid_body");
    ASSERT_EQ(p.size(), 2500u);
    ASSERT_EQ(p.acceleration_m_s2.size(), 3u * 2500u);
    for (int i = 0; i < 2500; ++i) {
      const auto expected = probe_rows(i, m.probes.size())[j];
      const auto k = static_cast<std::size_t>(i);
      ASSERT_EQ(p.time_s[k], glstat_row(i).time_s);
      for (std::size_t c = 0; c < 3; ++c) {
        ASSERT_EQ(p.displacement_m[3 * k + c], expected.displacement_m[c]);
        ASSERT_EQ(p.velocity_m_s[3 * k + c], expected.velocity_m_s[c]);
        ASSERT_EQ(p.acceleration_m_s2[3 * k + c], expected.acceleration_m_s2[c]);
      }
    }
  }
  const std::vector<GlstatSample> g = r.glstat();
  ASSERT_EQ(g.size(), 2500u);
  for (int i = 0; i < 2500; ++i) {
    const GlstatSample e = glstat_row(i);
    const GlstatSample& a = g[static_cast<std::size_t>(i)];
    ASSERT_EQ(a.time_s, e.time_s);
    ASSERT_EQ(a.kinetic_energy_J, e.kinetic_energy_J);
    ASSERT_EQ(a.internal_energy_J, e.internal_energy_J);
    ASSERT_EQ(a.hourglass_energy_J, e.hourglass_energy_J);
    ASSERT_EQ(a.contact_energy_J, e.contact_energy_J);
    ASSERT_EQ(a.external_work_J, e.external_work_J);
    ASSERT_EQ(a.total_energy_J, e.total_energy_J);
    ASSERT_EQ(a.energy_balance_error, e.energy_balance_error);
  }
}

TEST(ResultReader, ReadsWhatAWriterHasFlushedSoFar) {
  const auto m = small_model();
  const std::string dir = fresh_dir("out");
  ResultWriter w(dir, m, ResultWriterOptions{1000, 1e9, 256});
  write_rows(w, 1500, m.probes.size());  // 1000 flushed, 500 buffered
  const ResultReader r(w.h5_path());
  EXPECT_EQ(r.probe("head").size(), 1000u);
  EXPECT_EQ(r.glstat().size(), 1000u);
}

TEST(ResultReader, UnknownProbeListsTheProbesOfTheFile) {
  const auto m = small_model();
  const std::string dir = fresh_dir("out");
  { ResultWriter w(dir, m); }
  const ResultReader r(dir + "/result.h5");
  try {
    r.probe("toe");
    FAIL() << "no error for an unknown probe";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no probe named 'toe'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("2 probe(s): head, tip"), std::string::npos) << msg;
  }
}

TEST(ResultReader, ProbeNamesWithSlashes) {
  auto m = small_model();
  m.probes[1].name = "dummy/head";  // stored as the link dummy_head, name attribute kept
  const std::string dir = fresh_dir("out");
  {
    ResultWriter w(dir, m);
    write_rows(w, 3, m.probes.size());
  }
  const ResultReader r(dir + "/result.h5");
  EXPECT_EQ(r.probe_names(), (std::vector<std::string>{"dummy/head", "tip"}));
  EXPECT_EQ(r.probe("dummy/head").link, "dummy_head");
  EXPECT_EQ(r.probe("dummy_head").name, "dummy/head");
  EXPECT_EQ(r.probe("dummy/head").size(), 3u);
}

TEST(ResultReader, NotACrashlinkResult) {
  const std::string dir = fresh_dir("out");
  EXPECT_THROW(ResultReader(dir + "/missing.h5"), ResultFileError);
  const std::string other = dir + "/other.h5";
  {
    FileHandle f = create_file(other);  // a valid HDF5 file without the format attribute
  }
  try {
    ResultReader r(other);
    FAIL() << "accepted a file that is not a crashlink result";
  } catch (const ResultFileError& e) {
    EXPECT_NE(std::string(e.what()).find("not a crashlink result file"), std::string::npos)
        << e.what();
  }
}

// ---- `crashlink hic` on a result file -----------------------------------------------------------

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CommandRun run_crashlink(const std::string& args) {
  CommandRun r;
  const std::string cmd =
      "'" + std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink' " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) r.output += buf.data();
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

double hic_value(const std::string& out, int window) {
  std::smatch m;
  const std::regex re("HIC" + std::to_string(window) + R"( = ([0-9.]+) \(t1 = )");
  return std::regex_search(out, m, re) ? std::stod(m[1]) : NAN;
}

/// A result whose "head" probe accelerates along (0.6, 0, -0.8) with a half-sine of 80 g over
/// 10 ms starting at 2 ms; samples every 100 us, with +/-20 us jitter if `jitter`.
std::string head_impact_result(const std::string& dir, bool jitter) {
  const auto m = small_model();
  ResultWriter w(dir, m);
  const double g = 9.80665, A = 80.0, T = 0.010;
  for (int i = 0; i <= 300; ++i) {
    const double t = 1e-4 * i + (jitter && i % 300 != 0 ? 2e-5 * std::sin(1.7 * i) : 0.0);
    GlstatSample gl;
    gl.time_s = t;
    std::vector<ProbeSample> p(2);
    const double a =
        (t >= 0.002 && t <= 0.002 + T) ? A * g * std::sin(std::numbers::pi * (t - 0.002) / T) : 0;
    p[1].acceleration_m_s2[0] = 0.6 * a;
    p[1].acceleration_m_s2[2] = -0.8 * a;
    w.append_history(gl, p);
  }
  return w.h5_path();
}

TEST(CmdHicResult, HalfSineHeadProbe) {
  const std::string bin = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";
  ASSERT_TRUE(std::filesystem::exists(bin)) << bin << " is not built";
  // Closed form 0.41465 A^2.5 T (the optimal 6.7 ms window fits both windows).
  const double expected = 0.414646 * std::pow(80.0, 2.5) * 0.010;
  const std::string uniform = head_impact_result(fresh_dir("uniform"), false);

  const CommandRun raw = run_crashlink("hic " + uniform + " --probe head --cfc none");
  ASSERT_EQ(raw.exit_code, 0) << raw.output;
  std::printf("%s", raw.output.c_str());
  EXPECT_NEAR(hic_value(raw.output, 15) / expected, 1.0, 5e-3) << raw.output;
  EXPECT_NEAR(hic_value(raw.output, 36) / expected, 1.0, 5e-3) << raw.output;
  EXPECT_NE(raw.output.find("peak resultant acceleration = 80 g"), std::string::npos) << raw.output;

  const CommandRun filtered = run_crashlink("hic " + uniform + " --probe head");  // CFC 1000
  ASSERT_EQ(filtered.exit_code, 0) << filtered.output;
  std::printf("%s", filtered.output.c_str());
  EXPECT_NE(filtered.output.find("filter: CFC 1000"), std::string::npos) << filtered.output;
  EXPECT_NEAR(hic_value(filtered.output, 15) / expected, 1.0, 1e-2) << filtered.output;

  const std::string jittered = head_impact_result(fresh_dir("jitter"), true);
  const CommandRun resampled = run_crashlink("hic " + jittered + " --probe head --window 15");
  ASSERT_EQ(resampled.exit_code, 0) << resampled.output;
  std::printf("%s", resampled.output.c_str());
  EXPECT_NE(resampled.output.find("resampled linearly to a uniform"), std::string::npos)
      << resampled.output;
  EXPECT_NEAR(hic_value(resampled.output, 15) / expected, 1.0, 2e-2) << resampled.output;
  EXPECT_TRUE(std::isnan(hic_value(resampled.output, 36)));
}

TEST(CmdHicResult, UnknownOrMissingProbe) {
  const std::string path = head_impact_result(fresh_dir("out"), false);
  const CommandRun unknown = run_crashlink("hic " + path + " --probe toe");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("no probe named 'toe'; the file has 2 probe(s): head, tip"),
            std::string::npos)
      << unknown.output;
  const CommandRun none = run_crashlink("hic " + path);
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("--probe NAME; the file has probe(s): head, tip"), std::string::npos)
      << none.output;
}

}  // namespace
}  // namespace crashlink::io
