// Sampling helpers (solver/signal/sampling.h) and the CSV input of `crashlink hic`
// (solver/signal/signal_csv.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "solver/signal/sampling.h"
#include "solver/signal/signal_csv.h"

namespace crashlink::signal {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_signal_tests";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

/// The InputError message of read_signal_csv(path), "" if it did not throw.
std::string csv_error(const std::string& path) {
  try {
    read_signal_csv(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Sampling, UniformAndNot) {
  const std::vector<double> u{0.0, 1e-4, 2e-4, 3e-4};
  const Sampling s = sampling_of(u);
  EXPECT_TRUE(s.uniform());
  EXPECT_NEAR(s.mean_step_s, 1e-4, 1e-18);
  const std::vector<double> v{0.0, 1e-4, 2.5e-4, 3e-4};
  EXPECT_FALSE(sampling_of(v).uniform());
  EXPECT_NEAR(sampling_of(v).min_step_s, 0.5e-4, 1e-18);
  EXPECT_NEAR(sampling_of(v).max_step_s, 1.5e-4, 1e-18);
}

TEST(Sampling, ResampleLinearIsExactOnLines) {
  const std::vector<double> t{0.0, 0.3e-3, 0.4e-3, 1.0e-3}, x{1.0, 1.6, 1.8, 3.0};  // 1 + 2000 t
  std::vector<double> tu;
  const auto y = resample_linear(t, x, 1e-4, &tu);
  ASSERT_EQ(y.size(), 11u);
  for (std::size_t k = 0; k < y.size(); ++k) {
    EXPECT_NEAR(tu[k], 1e-4 * static_cast<double>(k), 1e-15);
    EXPECT_NEAR(y[k], 1.0 + 2000.0 * tu[k], 1e-12);
  }
  // Interleaved components.
  const std::vector<double> xyz{0, 0, 1, 3, 30, 1, 4, 40, 1, 10, 100, 1};
  const auto r = resample_linear(t, xyz, 5e-4, nullptr, 3);
  ASSERT_EQ(r.size(), 9u);
  EXPECT_NEAR(r[3], 5.0, 1e-12);
  EXPECT_NEAR(r[4], 50.0, 1e-12);
  EXPECT_NEAR(r[6], 10.0, 1e-12);
}

TEST(Sampling, Resultant) {
  const std::vector<double> xyz{3.0, 4.0, 0.0, 0.0, 0.0, -9.80665};
  const auto r = resultant(xyz, 1.0 / kStandardGravity_m_s2);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(r[0], 5.0 / 9.80665, 1e-15);
  EXPECT_NEAR(r[1], 1.0, 1e-15);
}

TEST(SignalCsv, ReadsAWellFormedFile) {
  const auto path = write_file("good.csv",
                               "\xEF\xBB\xBF# head, test 12\r\n time_s , accel_g \r\n0,0\r\n\r\n"
                               "1e-4,+1.5\r\n2.0e-4, -2\r\n");
  const CsvSignal s = read_signal_csv(path);
  ASSERT_EQ(s.time_s.size(), 3u);
  EXPECT_EQ(s.time_s[1], 1e-4);
  EXPECT_EQ(s.accel_g[1], 1.5);
  EXPECT_EQ(s.accel_g[2], -2.0);
}

TEST(SignalCsv, ErrorsNameTheLineAndTheFix) {
  EXPECT_NE(csv_error("/nonexistent/x.csv").find("cannot open"), std::string::npos);
  EXPECT_NE(csv_error(write_file("empty.csv", "")).find("empty"), std::string::npos);
  const std::string header = csv_error(write_file("header.csv", "t,a\n0,1\n1,2\n"));
  EXPECT_NE(header.find(":1: header: found 't,a'"), std::string::npos) << header;
  const std::string number = csv_error(write_file("number.csv", "time_s,accel_g\n0,1\n1,abc\n"));
  EXPECT_NE(number.find(":3: accel_g: 'abc' is not a finite number"), std::string::npos) << number;
  const std::string nan = csv_error(write_file("nan.csv", "time_s,accel_g\n0,nan\n1,2\n"));
  EXPECT_NE(nan.find(":2: accel_g"), std::string::npos) << nan;
  const std::string order =
      csv_error(write_file("order.csv", "time_s,accel_g\n0,1\n0.002,2\n0.001,3\n"));
  EXPECT_NE(order.find(":4: time_s: time 0.001 s does not increase"), std::string::npos) << order;
  const std::string fields = csv_error(write_file("fields.csv", "time_s,accel_g\n0,1,2\n"));
  EXPECT_NE(fields.find(":2: row"), std::string::npos) << fields;
  const std::string one = csv_error(write_file("one.csv", "time_s,accel_g\n0,1\n"));
  EXPECT_NE(one.find("at least 2"), std::string::npos) << one;
}

}  // namespace
}  // namespace crashlink::signal
