// The result writer: layout of docs/design.md §4 / docs/result-format.md read back with the HDF5 C
// API and compared exactly (doubles are stored as IEEE binary64, so round trips are bitwise).
#include "solver/io/result_writer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

using test::fresh_dir;
using test::H5Reader;
using test::small_model;

GlstatSample glstat_row(int i) {
  const double t = 1e-4 * i;
  return GlstatSample{t, 1.0 + i, 2.0 + i, 0.1 * i, 0.01 * i, 3.0 * i, 1.0 + 2.0 * i, 1e-6 * i};
}

std::vector<ProbeSample> probe_rows(int i) {
  std::vector<ProbeSample> p(2);
  for (int j = 0; j < 2; ++j) {
    for (int c = 0; c < 3; ++c) {
      p[j].displacement_m[c] = 0.001 * i + c + 10 * j;
      p[j].velocity_m_s[c] = -0.5 * i + c + 10 * j;
      p[j].acceleration_m_s2[c] = 9.81 * i - c + 10 * j;
    }
  }
  return p;
}

void expect_history(const H5Reader& r, int rows) {
  const auto time = r.doubles("/history/glstat/time");
  ASSERT_EQ(time.size(), static_cast<std::size_t>(rows));
  const auto ek = r.doubles("/history/glstat/kinetic_energy");
  const auto ei = r.doubles("/history/glstat/internal_energy");
  const auto eh = r.doubles("/history/glstat/hourglass_energy");
  const auto ec = r.doubles("/history/glstat/contact_energy");
  const auto we = r.doubles("/history/glstat/external_work");
  const auto et = r.doubles("/history/glstat/total_energy");
  const auto err = r.doubles("/history/glstat/energy_balance_error");
  for (int i = 0; i < rows; ++i) {
    const GlstatSample g = glstat_row(i);
    const auto k = static_cast<std::size_t>(i);
    EXPECT_EQ(time[k], g.time_s);
    EXPECT_EQ(ek[k], g.kinetic_energy_J);
    EXPECT_EQ(ei[k], g.internal_energy_J);
    EXPECT_EQ(eh[k], g.hourglass_energy_J);
    EXPECT_EQ(ec[k], g.contact_energy_J);
    EXPECT_EQ(we[k], g.external_work_J);
    EXPECT_EQ(et[k], g.total_energy_J);
    EXPECT_EQ(err[k], g.energy_balance_error);
  }
  const char* names[2] = {"tip", "head"};
  for (int j = 0; j < 2; ++j) {
    const std::string base = std::string("/history/probes/") + names[j];
    EXPECT_EQ(r.doubles(base + "/time"), time);
    EXPECT_EQ(r.dims(base + "/displacement"), (std::vector<hsize_t>{hsize_t(rows), 3}));
    const auto u = r.doubles(base + "/displacement");
    const auto v = r.doubles(base + "/velocity");
    const auto a = r.doubles(base + "/acceleration");
    for (int i = 0; i < rows; ++i) {
      const ProbeSample p = probe_rows(i)[static_cast<std::size_t>(j)];
      for (int c = 0; c < 3; ++c) {
        const auto k = static_cast<std::size_t>(3 * i + c);
        EXPECT_EQ(u[k], p.displacement_m[c]);
        EXPECT_EQ(v[k], p.velocity_m_s[c]);
        EXPECT_EQ(a[k], p.acceleration_m_s2[c]);
      }
    }
  }
}

TEST(ResultWriter, WritesMeshHistoryStatesAndTimingExactly) {
  const std::string dir = fresh_dir("out");
  const model::Model m = small_model();
  const std::size_t n = m.nodes.count();
  std::vector<double> u(3 * n), v(3 * n), eps(1), vm(1), sig(6), eps2(2), vm2(2);
  {
    ResultWriter w(dir, m, ResultWriterOptions{7, 1e9, 4});  // 7 rows per flush, chunks of 4
    for (int i = 0; i < 25; ++i) w.append_history(glstat_row(i), probe_rows(i));
    EXPECT_EQ(w.history_rows_written(), 21u);  // three automatic flushes of 7
    for (int s = 0; s < 2; ++s) {
      for (std::size_t i = 0; i < 3 * n; ++i) {
        u[i] = 0.01 * s * static_cast<double>(i);
        v[i] = -1.0 * s + static_cast<double>(i);
      }
      eps = {0.1 * s};
      vm = {250e6 + s};
      sig = {1e6, 2e6, 3e6, 4e6, 5e6, 6e6 + s};
      eps2 = {0.0, 0.02 * s};
      vm2 = {1e8, 2e8 + s};
      FieldState fs{0.001 * s, u, v, {PartFieldState{eps, vm, sig}, PartFieldState{eps2, vm2, {}}}};
      w.write_field_state(fs);
    }
    w.write_timing(
        12.5, 0.75,
        {DomainTiming{"body", 10.0, 1000, 1e-6, 1}, DomainTiming{"wiper", 11.0, 8000, 1.25e-7, 2}});
    w.close();
    EXPECT_EQ(w.history_rows_written(), 25u);
    EXPECT_EQ(w.state_count(), 2u);
    w.close();  // idempotent
  }
  H5Reader r(dir + "/result.h5");
  EXPECT_EQ(r.attr_string("/", "format"), "crashlink-result");
  EXPECT_EQ(r.attr_int64("/", "format_version"), 1);
  // mesh
  EXPECT_EQ(r.doubles("/mesh/coordinates"), m.nodes.x0);
  EXPECT_EQ(r.dims("/mesh/coordinates"), (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(r.int64s("/mesh/node_ids"), m.nodes.id);
  EXPECT_EQ(r.strings("/mesh/part_names"), (std::vector<std::string>{"block", "plate"}));
  EXPECT_EQ(r.int32s("/mesh/parts/block/connectivity"), m.parts[0].connectivity);
  EXPECT_EQ(r.dims("/mesh/parts/block/connectivity"), (std::vector<hsize_t>{1, 8}));
  EXPECT_EQ(r.dims("/mesh/parts/plate/connectivity"), (std::vector<hsize_t>{2, 4}));
  EXPECT_EQ(r.int64s("/mesh/parts/plate/element_ids"), m.parts[1].element_id);
  EXPECT_EQ(r.attr_string("/mesh/parts/plate", "kind"), "shell4");
  EXPECT_EQ(r.attr_string("/mesh/parts/block", "kind"), "hex8");
  // history
  expect_history(r, 25);
  EXPECT_EQ(r.attr_string("/history/probes/tip", "kind"), "node");
  EXPECT_EQ(r.attr_int64("/history/probes/tip", "node_id"), 107);
  EXPECT_EQ(r.attr_string("/history/probes/head", "rigid_body"), "impactor");
  // states
  EXPECT_EQ(r.attr_int64("/states", "count"), 2);
  EXPECT_EQ(r.attr_double("/states/1", "time"), 0.001);
  EXPECT_EQ(r.doubles("/states/1/displacement"), u);
  EXPECT_EQ(r.doubles("/states/1/velocity"), v);
  const auto x = r.doubles("/states/1/coordinates");
  for (std::size_t i = 0; i < 3 * n; ++i) EXPECT_EQ(x[i], m.nodes.x0[i] + u[i]);
  EXPECT_EQ(r.doubles("/states/1/parts/block/eps_p"), eps);
  EXPECT_EQ(r.doubles("/states/1/parts/block/von_mises"), vm);
  EXPECT_EQ(r.doubles("/states/1/parts/block/stress"), sig);
  EXPECT_EQ(r.dims("/states/1/parts/block/stress"), (std::vector<hsize_t>{1, 6}));
  EXPECT_EQ(r.doubles("/states/1/parts/plate/von_mises"), vm2);
  EXPECT_FALSE(r.exists("/states/1/parts/plate/stress"));
  EXPECT_EQ(r.attr_double("/states/0", "time"), 0.0);
  // units on every dataset
  for (const auto& [path, units] : std::vector<std::pair<std::string, std::string>>{
           {"/mesh/coordinates", "m"},
           {"/history/glstat/time", "s"},
           {"/history/glstat/kinetic_energy", "J"},
           {"/history/glstat/total_energy", "J"},
           {"/history/glstat/energy_balance_error", "1"},
           {"/history/probes/head/time", "s"},
           {"/history/probes/head/displacement", "m"},
           {"/history/probes/head/velocity", "m/s"},
           {"/history/probes/head/acceleration", "m/s^2"},
           {"/states/0/displacement", "m"},
           {"/states/0/velocity", "m/s"},
           {"/states/0/parts/block/von_mises", "Pa"},
           {"/states/0/parts/block/stress", "Pa"},
           {"/states/0/parts/block/eps_p", "1"}}) {
    EXPECT_EQ(r.attr_string(path, "units"), units) << path;
  }
  // timing
  EXPECT_EQ(r.attr_double("/timing", "wall_seconds"), 12.5);
  EXPECT_EQ(r.attr_double("/timing", "coordinator_cpu_seconds"), 0.75);
  EXPECT_EQ(r.attr_double("/timing/wiper", "cpu_seconds"), 11.0);
  EXPECT_EQ(r.attr_int64("/timing/wiper", "cycles"), 8000);
  EXPECT_EQ(r.attr_double("/timing/wiper", "dt_min"), 1.25e-7);
  EXPECT_EQ(r.attr_int64("/timing/wiper", "elements"), 2);
  EXPECT_EQ(r.attr_int64("/timing/body", "cycles"), 1000);
  EXPECT_TRUE(std::filesystem::exists(dir + "/result.xdmf"));
}

TEST(ResultWriter, FlushedHistoryIsReadableWhileTheWriterIsOpen) {
  const std::string dir = fresh_dir("out");
  ResultWriter w(dir, small_model(), ResultWriterOptions{1000, 1e9, 16});
  for (int i = 0; i < 5; ++i) w.append_history(glstat_row(i), probe_rows(i));
  w.flush();
  for (int i = 5; i < 8; ++i) w.append_history(glstat_row(i), probe_rows(i));  // not flushed
  H5Reader r(w.h5_path());
  expect_history(r, 5);
}

TEST(ResultWriter, WallClockFlushWritesWithoutWaitingForTheSampleCount) {
  const std::string dir = fresh_dir("out");
  ResultWriter w(dir, small_model(), ResultWriterOptions{1000000, 0.0, 16});  // every sample
  for (int i = 0; i < 3; ++i) w.append_history(glstat_row(i), probe_rows(i));
  EXPECT_EQ(w.history_rows_written(), 3u);
}

TEST(ResultWriter, WriterDestroyedDuringUnwindingLeavesAReadableFile) {
  const std::string dir = fresh_dir("out");
  const model::Model m = small_model();
  std::vector<double> u(3 * m.nodes.count(), 0.5);
  try {
    ResultWriter w(dir, m, ResultWriterOptions{4, 1e9, 8});
    for (int i = 0; i < 10; ++i) w.append_history(glstat_row(i), probe_rows(i));
    w.write_field_state(FieldState{0.0, u, {}, {}});
    throw std::runtime_error("element 7 inverted");  // the run dies mid-way
  } catch (const std::runtime_error&) {
  }
  H5Reader r(dir + "/result.h5");
  expect_history(r, 10);  // the destructor flushed the two buffered rows too
  EXPECT_EQ(r.doubles("/states/0/displacement"), u);
  EXPECT_FALSE(r.exists("/states/0/velocity"));
}

// A process that dies without any destructor (std::_Exit, like a crash) keeps every flushed row.
TEST(ResultWriterDeathTest, ProcessKilledAfterAFlushLeavesTheFlushedHistory) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::string dir = fresh_dir("out");
  EXPECT_EXIT(
      {
        ResultWriter w(dir, small_model(), ResultWriterOptions{6, 1e9, 4});
        for (int i = 0; i < 15; ++i) w.append_history(glstat_row(i), probe_rows(i));  // 12 flushed
        std::_Exit(3);
      },
      ::testing::ExitedWithCode(3), "");
  H5Reader r(dir + "/result.h5");
  expect_history(r, 12);
}

TEST(ResultWriter, MisuseAndHdf5FailuresThrowResultFileErrorWithThePath) {
  const std::string dir = fresh_dir("out");
  ResultWriter w(dir, small_model());
  try {
    w.append_history(glstat_row(0), {});
    FAIL() << "expected ResultFileError";
  } catch (const ResultFileError& e) {
    EXPECT_NE(std::string(e.what()).find("0 probe samples given, the model has 2"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("result.h5"), std::string::npos) << e.what();
  }
  std::vector<double> short_u(5);
  EXPECT_THROW(w.write_field_state(FieldState{0.0, short_u, {}, {}}), ResultFileError);
  w.close();
  EXPECT_THROW(w.append_history(glstat_row(0), probe_rows(0)), ResultFileError);
  EXPECT_THROW(w.write_timing(1.0, 1.0, {}), ResultFileError);

  // An HDF5 failure: the target path is a directory, so H5Fcreate fails. No HDF5 stack on stderr.
  const std::string blocked = fresh_dir("blocked");
  std::filesystem::create_directories(blocked + "/result.h5");
  ::testing::internal::CaptureStderr();
  try {
    ResultWriter bad(blocked, small_model());
    FAIL() << "expected ResultFileError";
  } catch (const ResultFileError& e) {
    EXPECT_NE(std::string(e.what()).find(blocked + "/result.h5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("H5Fcreate"), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), blocked + "/result.h5");
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(ResultWriter, EmptyModelStillGivesAValidFile) {
  const std::string dir = fresh_dir("out");
  model::Model m;
  {
    ResultWriter w(dir, m);
    w.append_history(glstat_row(1), {});
    w.write_field_state(FieldState{0.0, {}, {}, {}});
  }
  H5Reader r(dir + "/result.h5");
  EXPECT_EQ(r.dims("/mesh/coordinates"), (std::vector<hsize_t>{0, 3}));
  EXPECT_EQ(r.doubles("/history/glstat/kinetic_energy"), std::vector<double>{2.0});
  EXPECT_EQ(r.attr_int64("/states", "count"), 1);
}

TEST(ResultWriter, DuplicatePartNamesAreAModelError) {
  model::Model m = small_model();
  m.parts[1].name = "block";
  EXPECT_THROW(ResultWriter(fresh_dir("out"), m), ModelError);
}

TEST(ResultWriter, ReadableWithH5pyThroughToolsReadResult) {
  if (!std::filesystem::exists("/usr/bin/python3") ||
      std::system("/usr/bin/python3 -c 'import h5py' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "/usr/bin/python3 with h5py (python3-h5py) not installed";
  }
  const std::string dir = fresh_dir("out");
  const model::Model m = small_model();
  std::vector<double> u(3 * m.nodes.count(), 0.25);
  {
    ResultWriter w(dir, m);
    for (int i = 0; i < 4; ++i) w.append_history(glstat_row(i), probe_rows(i));
    w.write_field_state(FieldState{0.002, u, u, {}});
    w.write_timing(3.0, 0.5, {DomainTiming{"body", 2.0, 40, 1e-6, 3}});
  }
  const std::string cmd = std::string("/usr/bin/python3 ") + CRASHLINK_SOURCE_DIR +
                          "/tools/read_result.py --units " + dir + "/result.h5";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, got);
  ASSERT_EQ(pclose(p), 0) << out;
  for (const char* expected :
       {"\"history_rows\": 4", "\"format\": \"crashlink-result\"", "\"tip\": 4",
        "\"states\": [\n  0.002\n ]", "\"cycles\": 40",
        "\"history/probes/head/acceleration\": \"m/s^2\"", "\"total_energy\": 7.0"}) {
    EXPECT_NE(out.find(expected), std::string::npos) << expected << " not in\n" << out;
  }
}

}  // namespace
}  // namespace crashlink::io
