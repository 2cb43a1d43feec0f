// A run at twice the computed stable step is caught by the guard with its message, and no NaN
// reaches the output (issue 2 acceptance). The same run at the default scale passes the guard.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>

#include "solver/run/run_single.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

model::Model vibrating_bar(double dt_scale) {
  auto m = bar(50, 0.25, 0.005, steel(0.3));
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    m.initial_velocities.push_back({{static_cast<std::int32_t>(i)}, {0.0, 0.0, 0.0}});
  auto end = nodes_where(m, [](const Vec3& x) { return x[0] < 1e-9; });
  m.loads.push_back({"push", end, 0, model::Curve::constant(100.0)});
  m.probes.push_back({"end", model::Probe::Kind::Node, end[0]});
  m.controls.end_time_s = 2e-4;
  m.controls.dt_scale = dt_scale;
  return m;
}

std::vector<double> read_dataset(const std::string& file, const std::string& path) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file << " does not open";
  hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << path;
  hid_t sp = H5Dget_space(d);
  const auto n = H5Sget_simple_extent_npoints(sp);
  std::vector<double> v(static_cast<std::size_t>(n));
  if (n > 0) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  return v;
}

}  // namespace

TEST(Guard, TwiceTheStableStepIsCaughtWithoutNaNInOutput) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_guard_unstable_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  auto m = vibrating_bar(1.8);  // 2 x the default safety factor 0.9
  run::RunOptions opt;
  opt.out_dir = dir.string();
  opt.progress = false;
  const auto s = run::run_single_domain(m, opt);
  ASSERT_TRUE(s.failed) << "a run at 1.8 x the stable step was not stopped";
  EXPECT_NE(s.failure.find("energy balance"), std::string::npos) << s.failure;
  EXPECT_NE(s.failure.find("cycle"), std::string::npos) << s.failure;
  EXPECT_NE(s.failure.find("dt_scale"), std::string::npos) << s.failure;
  for (const char* ds : {"/history/glstat/time", "/history/glstat/kinetic_energy",
                         "/history/glstat/total_energy", "/history/probes/end/velocity"}) {
    const auto v = read_dataset(s.result_h5, ds);
    EXPECT_FALSE(v.empty()) << ds;
    for (double x : v) ASSERT_TRUE(std::isfinite(x)) << ds;
  }
}

TEST(Guard, DefaultStepPasses) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_guard_stable_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  auto m = vibrating_bar(0.9);
  run::RunOptions opt;
  opt.out_dir = dir.string();
  opt.progress = false;
  const auto s = run::run_single_domain(m, opt);
  EXPECT_FALSE(s.failed) << s.failure;
  EXPECT_LT(std::abs(s.energy.balance_error()), 0.01);
}
