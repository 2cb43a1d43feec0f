// Finite and cylindrical rigid walls (model::RigidWall::Shape, *RIGIDWALL_PLANAR_FINITE,
// *RIGIDWALL_GEOMETRIC_FLAT / _CYLINDER): an elastic bar falls on them.
//  - a finite plane under the whole bar gives the infinite plane's answer to the bit (the same
//    nodes stopped the same way); one beside the bar lets it fall through;
//  - a cylinder of large radius under the bar (axis across it) stops it on its surface: no node
//    inside, the rebound within 1 % of the plane's (the face is 0.0125 mm off flat), the energy
//    balance kept; a finite cylinder whose length lies beside the bar lets it through.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "solver/deck/model_from_deck.h"
#include "solver/integration/solver.h"
#include "tests/integration/run_helpers.h"

namespace crashlink {
namespace {

constexpr double kL = 50.0, kA = 10.0;  // mm: length, side
constexpr int kLayers = 25;             // 2 mm elements
constexpr double kV = 5000.0;           // mm/s toward the wall
constexpr double kGap = 0.05;           // mm

/// Three free-format fields (17 digits, then a comma): the point (x, y, z) mm of the bar's frame
/// turned by `r`.
std::string pt(const Mat3& r, double x, double y, double z) {
  const Vec3 q = mul(r, Vec3{x, y, z});
  char s[80];
  std::snprintf(s, sizeof s, "%.17g,%.17g,%.17g,", q[0], q[1], q[2]);
  return s;
}

/// The bar along z in [gap, gap + L] mm (x, y in [0, 10]), moving at -v, then `wall` (the
/// keyword and its cards, NSID 0: every node); everything turned by `r`.
std::string bar_deck(const std::string& wall, const Mat3& r = identity3()) {
  std::string s = "*KEYWORD\n*NODE\n";
  int id = 1;
  for (int k = 0; k <= kLayers; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        char line[80];
        const Vec3 x = mul(r, Vec3{kA * i, kA * j, kGap + kL * k / kLayers});
        std::snprintf(line, sizeof line, "%8d%16.9e%16.9e%16.9e\n", id++, x[0], x[1], x[2]);
        s += line;
      }
  s += "*ELEMENT_SOLID\n";
  for (int k = 0; k < kLayers; ++k) {
    const int b = 4 * k + 1, t = b + 4;
    char line[100];
    std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8d%8d\n", k + 1, 1, b, b + 1, b + 3,
                  b + 2, t, t + 1, t + 3, t + 2);
    s += line;
  }
  s += "*PART\nbar\n         1         1         1\n*SECTION_SOLID\n         1         1\n"
       "*MAT_ELASTIC\n         1   7.85e-9  210000.0       0.0\n"
       "*INITIAL_VELOCITY_GENERATION\n         1         2       0.0";
  const Vec3 v = mul(r, Vec3{0.0, 0.0, -kV});
  char line[80];
  std::snprintf(line, sizeof line, "%10.3f%10.3f%10.3f\n\n", v[0], v[1], v[2]);
  s += line;
  s += "*CONTROL_BULK_VISCOSITY\n       0.0       0.0\n";
  s += wall;
  s += "*CONTROL_TERMINATION\n   4.0E-05\n*END\n";
  return s;
}

struct BarRun {
  double vz_end = 0.0;    ///< mass-weighted mean at the end [m/s]
  double z_min = 1e9;     ///< the lowest node [m]
  double inside = 1e9;    ///< the least distance from the cylinder's axis less its radius [m]
  double worst = 0.0;     ///< largest |balance| [J]
  double e0 = 0.0;        ///< initial energy [J]
  std::vector<double> v;  ///< velocities at the end
};

/// Runs the bar on `wall`, everything turned by `rot`; measures in the bar's frame;
/// `axis_y_z_r`: a cylinder's axis (along the frame's x) at (y, z), radius, in m.
BarRun run_on(const std::string& wall, const double* axis_y_z_r = nullptr,
              const Mat3& rot = identity3()) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_wall_shapes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = (dir / "bar.k").string();
  std::ofstream(path) << bar_deck(wall, rot);
  const model::Model m = deck::read_deck(path, {"mm-t-s", {}}).model;
  std::filesystem::remove_all(dir);
  integration::Solver s(m);
  BarRun r;
  testing::run(s, [&](const integration::Solver& sv) {
    if (r.e0 == 0.0) r.e0 = sv.energy().total_J();
    r.worst = std::max(r.worst, std::abs(sv.energy().balance_J()));
    const auto& u = sv.displacement();
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      const Vec3 x = mul(transpose(rot),
                         Vec3{m.nodes.x0[3 * i] + u[3 * i], m.nodes.x0[3 * i + 1] + u[3 * i + 1],
                              m.nodes.x0[3 * i + 2] + u[3 * i + 2]});
      const double y = x[1], z = x[2];
      r.z_min = std::min(r.z_min, z);
      if (axis_y_z_r)
        r.inside =
            std::min(r.inside, std::hypot(y - axis_y_z_r[0], z - axis_y_z_r[1]) - axis_y_z_r[2]);
    }
  });
  double p = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    for (std::size_t d = 0; d < 3; ++d) p += s.mass()[i] * rot[d][2] * s.velocity_mid()[3 * i + d];
    mass += s.mass()[i];
  }
  r.vz_end = p / mass;
  r.v = s.velocity_mid();
  return r;
}

const std::string kPlane =
    "*RIGIDWALL_PLANAR\n         0\n       0.0       0.0       0.0       0.0       0.0       1.0\n";

TEST(RigidWallShapes, FinitePlaneUnderTheBarIsTheInfinitePlane) {
  const BarRun a = run_on(kPlane);
  const BarRun b = run_on(
      "*RIGIDWALL_PLANAR_FINITE\n         0\n"
      "      -5.0      -5.0       0.0      -5.0      -5.0       1.0\n"
      "      15.0      -5.0       0.0      20.0      20.0\n");
  const BarRun c = run_on(
      "*RIGIDWALL_GEOMETRIC_FLAT\n         0\n"
      "      15.0      -5.0       0.0      15.0      -5.0       1.0\n"
      "      15.0      15.0       0.0      20.0      20.0\n");
  std::printf("[measured] finite plane: rebound %.6f v (infinite %.6f v), lowest node %.3e m\n",
              b.vz_end / (kV * 1e-3), a.vz_end / (kV * 1e-3), b.z_min);
  EXPECT_GT(a.vz_end, 0.9 * kV * 1e-3) << "the bar left the plane upward";
  EXPECT_EQ(b.v, a.v) << "the same nodes stopped the same way";
  EXPECT_EQ(c.v, a.v) << "GEOMETRIC_FLAT: the edge along y, m = n x l along -x";
}

TEST(RigidWallShapes, FinitePlaneBesideTheBarLetsItFall) {
  const BarRun b = run_on(
      "*RIGIDWALL_PLANAR_FINITE\n         0\n"
      "      11.0      -5.0       0.0      11.0      -5.0       1.0\n"
      "      31.0      -5.0       0.0      20.0      20.0\n");
  EXPECT_NEAR(b.vz_end, -kV * 1e-3, 1e-9);
  EXPECT_LT(b.z_min, -0.1e-3) << "through where the wall is not";
}

TEST(RigidWallShapes, CylinderStopsTheBarOnItsSurface) {
  // axis along x at y = 5 mm, z = -1000 mm, radius 1000 mm: the top at z = 0 under the bar's
  // middle, its face corners (y = 0, 10) 0.0125 mm lower
  const double axis[3] = {5e-3, -1.0, 1.0};
  const BarRun a = run_on(kPlane);
  const BarRun b = run_on(
      "*RIGIDWALL_GEOMETRIC_CYLINDER\n         0\n"
      "    -100.0       5.0   -1000.0     100.0       5.0   -1000.0\n"
      "    1000.0\n",
      axis);
  std::printf(
      "[measured] cylinder R 1 m: rebound %.6f v (plane %.6f v), deepest inside %.3e m, "
      "|balance| %.2e E0\n",
      b.vz_end / (kV * 1e-3), a.vz_end / (kV * 1e-3), -b.inside, b.worst / b.e0);
  EXPECT_GE(b.inside, -1e-12) << "no node inside the cylinder";
  EXPECT_NEAR(b.vz_end, a.vz_end, 0.01 * kV * 1e-3);
  EXPECT_LT(b.worst, 0.01 * b.e0);
  // a finite cylinder from x = 20 to 120 mm: beside the bar (x in [0, 10])
  const BarRun c = run_on(
      "*RIGIDWALL_GEOMETRIC_CYLINDER\n         0\n"
      "      20.0       5.0   -1000.0     120.0       5.0   -1000.0\n"
      "    1000.0     100.0\n",
      axis);
  EXPECT_NEAR(c.vz_end, -kV * 1e-3, 1e-9);
  EXPECT_LT(c.inside, -0.1e-3) << "into the infinite cylinder's place";
}

// The same walls turned about a skew axis (no wall along a coordinate axis, the rectangle's
// edge and the cylinder's axis oblique; the points in free format to 17 digits): the finite
// plane still gives the infinite plane's answer, the cylinder still stops the bar on its surface.
TEST(RigidWallShapes, TurnedWallsGiveTheSameAnswers) {
  const Vec3 axis = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
  const double th = 0.7, c = std::cos(th), sn = std::sin(th);
  Mat3 r{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      r[i][j] = (1.0 - c) * axis[i] * axis[j] + (i == j ? c : 0.0);
  r[0][1] -= sn * axis[2];
  r[1][0] += sn * axis[2];
  r[0][2] += sn * axis[1];
  r[2][0] -= sn * axis[1];
  r[1][2] -= sn * axis[0];
  r[2][1] += sn * axis[0];
  const BarRun plane = run_on(
      "*RIGIDWALL_PLANAR\n         0\n" + pt(r, 0, 0, 0) + pt(r, 0, 0, 1) + "\n", nullptr, r);
  const BarRun finite = run_on("*RIGIDWALL_PLANAR_FINITE\n         0\n" + pt(r, -5, -5, 0) +
                                   pt(r, -5, -5, 1) + "\n" + pt(r, 15, -5, 0) + "20.0,20.0\n",
                               nullptr, r);
  const double axis_m[3] = {5e-3, -1.0, 1.0};
  const BarRun cylinder = run_on("*RIGIDWALL_GEOMETRIC_CYLINDER\n         0\n" +
                                     pt(r, -100, 5, -1000) + pt(r, 100, 5, -1000) + "\n1000.0\n",
                                 axis_m, r);
  std::printf(
      "[measured] turned walls: rebound plane %.6f v, finite %.6f v, cylinder %.6f v; "
      "lowest node %.2e m, deepest in the cylinder %.2e m\n",
      plane.vz_end / (kV * 1e-3), finite.vz_end / (kV * 1e-3), cylinder.vz_end / (kV * 1e-3),
      plane.z_min, -cylinder.inside);
  EXPECT_GT(plane.vz_end, 0.9 * kV * 1e-3);
  EXPECT_NEAR(finite.vz_end, plane.vz_end, 1e-9 * kV * 1e-3);  // the same nodes stopped
  EXPECT_GE(plane.z_min, -1e-12);      // nothing through (the turned coordinates' round-off)
  EXPECT_GE(cylinder.inside, -1e-12);  // no node inside the cylinder
  EXPECT_NEAR(cylinder.vz_end, plane.vz_end, 0.01 * kV * 1e-3);
  EXPECT_LT(cylinder.worst, 0.01 * cylinder.e0);
}

}  // namespace
}  // namespace crashlink
