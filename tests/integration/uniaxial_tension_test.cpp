// Uniaxial tension with hardening follows the input curve within 1 % (issue 2 acceptance), for a
// solid and a shell, through the whole solver (kinematics, return mapping, output).
// One element pulled slowly (quasi-static: the ramp lasts ~100 element periods, so inertia
// stresses are < 0.1 % of yield) with symmetry conditions that leave the lateral faces free.
// Checks: sigma_xx = sigma_y(eps_p) within 1 % once plastic; eps_p = ln(L/L0) - sigma/E within
// 1 % of the total strain (hypoelastic rate form integrates D to the logarithmic strain).
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

struct Pull {
  double strain;    // ln(L/L0)
  double sigma_xx;  // Pa
  double eps_p;
};

std::vector<Pull> pull(model::Model& m, double length, double speed, double t_end) {
  const auto right = nodes_where(m, [&](const Vec3& x) { return std::abs(x[0] - length) < 1e-9; });
  model::Curve ramp{{0.0, 0.1 * t_end, t_end}, {0.0, speed, speed}};
  m.prescribed_velocities.push_back({"pull", right, 0, ramp});
  m.controls.end_time_s = t_end;
  integration::Solver s(m);
  std::vector<Pull> out;
  std::vector<double> vm(1), ep(1), st(6);
  run(s, [&](const integration::Solver& sv) {
    sv.element_output(0, {vm.data(), ep.data(), st.data()});
    const double ux = sv.displacement()[3 * static_cast<std::size_t>(right[0])];
    out.push_back({std::log((length + ux) / length), st[0], ep[0]});
  });
  return out;
}

void check(const std::vector<Pull>& h, const materials::Material& mat, const char* what) {
  int plastic = 0;
  double worst = 0.0;
  for (const auto& p : h) {
    if (p.eps_p < 0.01) continue;
    ++plastic;
    worst = std::max(worst, std::abs(p.sigma_xx / mat.hardening.yield(p.eps_p) - 1.0));
    EXPECT_NEAR(p.sigma_xx / mat.hardening.yield(p.eps_p), 1.0, 0.01) << "eps_p " << p.eps_p;
    EXPECT_NEAR(p.eps_p, p.strain - p.sigma_xx / mat.youngs_modulus_Pa, 0.01 * p.strain);
  }
  EXPECT_GT(plastic, 100) << "the test never went plastic";
  EXPECT_GT(h.back().eps_p, 0.15);  // past the first kink of the curve (0.1)
  std::printf(
      "[measured] uniaxial tension (%s): max |sigma/sigma_y(eps_p) - 1| = %.3e up to eps_p %.3f\n",
      what, worst, h.back().eps_p);
}

}  // namespace

TEST(UniaxialTension, SolidFollowsHardeningCurve) {
  const double a = 0.01;
  model::Model m;
  m.name = "one hex";
  m.materials.push_back(j2_steel());
  model::Part p;
  p.name = "cube";
  p.material = 0;
  model::generate_box(m, p, {{0, 0, 0}, {a, a, a}, {1, 1, 1}});
  fix(m, nodes_where(m, [](const Vec3& x) { return x[0] < 1e-9; }), model::kUx);
  fix(m, nodes_where(m, [](const Vec3& x) { return x[1] < 1e-9; }), model::kUy);
  fix(m, nodes_where(m, [](const Vec3& x) { return x[2] < 1e-9; }), model::kUz);
  const auto h = pull(m, a, 0.2, 0.01);  // 2 mm: total strain ~0.18
  check(h, m.materials[0], "solid");
}

TEST(UniaxialTension, ShellFollowsHardeningCurve) {
  const double a = 0.01;
  model::Model m;
  m.name = "one shell";
  m.materials.push_back(j2_steel());
  model::Part p;
  p.name = "sheet";
  p.material = 0;
  p.thickness_m = 0.001;
  p.through_thickness_points = 5;
  model::generate_plate(m, p, {{0, 0, 0}, {a, 0, 0}, {0, a, 0}, {1, 1}, 0.0});
  fix(m, nodes_where(m, [](const Vec3&) { return true; }),
      model::kUz | model::kRx | model::kRy | model::kRz);
  fix(m, nodes_where(m, [](const Vec3& x) { return x[0] < 1e-9; }), model::kUx);
  fix(m, nodes_where(m, [](const Vec3& x) { return x[1] < 1e-9; }), model::kUy);
  const auto h = pull(m, a, 0.2, 0.01);
  check(h, m.materials[0], "shell");
}
