// A rigid wall (model::RigidWall, read from *RIGIDWALL_PLANAR) against the 1-D answer: an
// elastic bar (nu = 0, so one-dimensional) at v hits a fixed wall. It stays on the wall for 2L/c
// (c = sqrt(E/rho)) and leaves with -v, all its energy back in motion; no node crosses the wall.
// The wall stops each arriving node dead (a perfectly plastic node impact, as LS-DYNA's
// stonewall): the face nodes' kinetic energy, 1/(2 n) of E0 for n element layers, is the wall's
// work, booked as external work so the balance holds. No bulk viscosity: the 1-D answer has no
// dissipation (with the defaults, Q1 0.06 and Q2 1.5, the shock front's heat leaves 0.964 v).
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
#include "solver/io/result_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

constexpr double kRho = 7.85e-9, kE = 2.1e5;  // t/mm^3, MPa: steel, nu = 0
constexpr double kL = 100.0, kA = 10.0;       // mm: length, side
constexpr int kLayers = 50;                   // elements along the bar (2 mm)
constexpr double kV = 5000.0;                 // mm/s: 5 m/s toward the wall
constexpr double kGap = 0.05;                 // mm between the bar and the wall

/// The bar along z in [gap, gap + L] mm, moving at -v toward a wall z = 0 with normal +z: NSID the
/// nodes of its lower face (and all the nodes with `all_nodes`); everything turned by `r`.
/// With `wall_mass_t` > 0 the bar is at rest and the wall moves (*RIGIDWALL_PLANAR_MOVING, mass in
/// t) toward it at kV.
std::string bar_deck(bool all_nodes, const Mat3& r, bool two_parts = false,
                     double wall_mass_t = 0.0) {
  auto turned = [&](double x, double y, double z) { return mul(r, Vec3{x, y, z}); };
  std::string s = "*KEYWORD\n*NODE\n";
  int id = 1;
  for (int k = 0; k <= kLayers; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        char line[80];
        const Vec3 x = turned(kA * i, kA * j, kGap + kL * k / kLayers);
        std::snprintf(line, sizeof line, "%8d%16.9e%16.9e%16.9e\n", id++, x[0], x[1], x[2]);
        s += line;
      }
  s += "*ELEMENT_SOLID\n";
  for (int k = 0; k < kLayers; ++k) {
    const int b = 4 * k + 1, t = b + 4;
    char line[100];
    std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8d%8d\n", k + 1,
                  two_parts && k >= kLayers / 2 ? 2 : 1, b, b + 1, b + 3, b + 2, t, t + 1, t + 3,
                  t + 2);
    s += line;
  }
  s += "*PART\nbar\n         1         1         1\n";
  if (two_parts) s += "*PART\ntop\n         2         1         1\n";
  s += "*SECTION_SOLID\n         1         1\n"
       "*MAT_ELASTIC\n         1   7.85e-9  210000.0       0.0\n"
       "*SET_NODE_LIST\n        10\n         1         2         3         4\n";
  const Vec3 v = turned(0.0, 0.0, wall_mass_t > 0.0 ? 0.0 : -kV), head = turned(0.0, 0.0, 1000.0);
  if (two_parts) s += "*SET_PART_LIST\n         7\n         1         2\n";
  char line[120];
  std::snprintf(line, sizeof line,
                "*INITIAL_VELOCITY_GENERATION\n%10d%10d       0.0%10.3f%10.3f%10.3f\n\n",
                two_parts ? 7 : 1, two_parts ? 1 : 2, v[0], v[1], v[2]);
  s += line;
  s += wall_mass_t > 0.0 ? "*CONTROL_BULK_VISCOSITY\n       0.0       0.0\n"
                           "*RIGIDWALL_PLANAR_MOVING_ID\n         1floor\n"
                         : "*CONTROL_BULK_VISCOSITY\n       0.0       0.0\n"
                           "*RIGIDWALL_PLANAR_ID\n         1floor\n";
  s += all_nodes ? "         0\n" : "        10\n";
  std::snprintf(line, sizeof line, "       0.0       0.0       0.0%10.4f%10.4f%10.4f\n", head[0],
                head[1], head[2]);
  s += line;
  if (wall_mass_t > 0.0) {
    std::snprintf(line, sizeof line, "%10.4e%10.1f\n", wall_mass_t, kV);
    s += line;
  }
  s += "*CONTROL_TERMINATION\n   8.0E-05\n*END\n";
  return s;
}

struct WallRun {
  double e0 = 0.0, worst = 0.0, external = 0.0, kinetic_end = 0.0;
  double vz_end = 0.0;                ///< mass-weighted mean at the end [m/s]
  double z_min = 1e9;                 ///< lowest node position seen [m]
  double touch = -1.0, leave = -1.0;  ///< the lower face's first arrival and last departure [s]
  double impulse = 0.0;               ///< sum of the wall's force along its normal x dt [N s]
  double wall_work = 0.0;             ///< the wall's own work account at the end [J]
  double mass = 0.0;                  ///< the bar's [kg]
};

WallRun run_bar(bool all_nodes, const Mat3& rot = identity3()) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_rigid_wall_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = (dir / "bar.k").string();
  std::ofstream(path) << bar_deck(all_nodes, rot);
  const model::Model m = deck::read_deck(path, {"mm-t-s", {}}).model;
  std::filesystem::remove_all(dir);
  EXPECT_EQ(m.rigid_walls.size(), 1u);
  EXPECT_EQ(m.rigid_walls[0].name, "floor");
  EXPECT_EQ(m.rigid_walls[0].nodes.size(), all_nodes ? m.nodes.count() : 4u);
  integration::Solver s(m);
  WallRun r;
  testing::run(s, [&](const integration::Solver& sv) {
    const auto& e = sv.energy();
    if (r.e0 == 0.0) r.e0 = e.total_J();
    r.worst = std::max(r.worst, std::abs(e.balance_J()));
    const auto& u = sv.displacement();
    double face = 1e9;
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      // the height above the wall, along its normal (the turned z axis)
      double z = 0.0;
      for (std::size_t d = 0; d < 3; ++d) z += rot[d][2] * (m.nodes.x0[3 * i + d] + u[3 * i + d]);
      r.z_min = std::min(r.z_min, z);
      if (i < 4) face = std::min(face, z);
    }
    const bool on_wall = face < 1e-9;  // within 1 nm of the plane
    const Vec3 f = sv.wall_force_N(0);
    if (!sv.finished()) r.impulse += dot(f, m.rigid_walls[0].normal) * sv.dt_s();
    if (on_wall && r.touch < 0.0) r.touch = sv.time_s();
    if (on_wall) r.leave = sv.time_s();
  });
  const auto& e = s.energy();
  r.external = e.external_work_J;
  r.kinetic_end = e.kinetic_J;
  double p = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    for (std::size_t d = 0; d < 3; ++d) p += s.mass()[i] * rot[d][2] * s.velocity_mid()[3 * i + d];
    mass += s.mass()[i];
  }
  r.vz_end = p / mass;
  r.mass = mass;
  r.wall_work = s.wall_work_J(0);
  return r;
}

TEST(RigidWall, ElasticBarReboundsAfterTwoLOverC) {
  const WallRun r = run_bar(false);
  const double c_mm_s = std::sqrt(kE / kRho);
  const double two_l_c = 2.0 * kL / c_mm_s;
  const double duration = r.leave - r.touch;
  std::printf(
      "[measured] bar on a rigid wall (%d layers, 5 m/s): on the wall %.4f x 2L/c, rebound %.4f "
      "v, kinetic at the end %.4f E0, wall work %.4f E0 (face nodes' share 1/(2n) = %.4f), "
      "largest |balance| %.2e E0, lowest node %.3e m\n",
      kLayers, duration / two_l_c, r.vz_end / (kV * 1e-3), r.kinetic_end / r.e0, r.external / r.e0,
      1.0 / (2.0 * kLayers), r.worst / r.e0, r.z_min);
  EXPECT_NEAR(r.e0, 0.5 * (kRho * 1e12) * (kL * kA * kA * 1e-9) * 25.0, 1e-6 * r.e0);
  ASSERT_GT(r.touch, 0.0);
  // the bar reaches the wall after the gap (10 us at 5 m/s), within a step (0.35 us)
  EXPECT_NEAR(r.touch, kGap / kV, 5e-7);
  EXPECT_NEAR(duration / two_l_c, 1.0, 0.03);
  // leaves upward at v, less what the wall took (the face nodes' 1.3 % of E0) and what rings
  EXPECT_NEAR(r.vz_end / (kV * 1e-3), 1.0, 0.02);
  EXPECT_GE(r.z_min, -1e-12);  // nothing crosses
  EXPECT_LT(r.worst / r.e0, 0.01);
  // the wall's work: minus the kinetic energy of the nodes it stopped, a few layers' worth
  EXPECT_LT(r.external, 0.0);
  EXPECT_GT(r.external, -0.05 * r.e0);
  // its force history (rwforc): the impulse is the bar's change of momentum, M (v_end + v); its
  // own work account is the model's external work (the only external force)
  const double dp = r.mass * (r.vz_end + kV * 1e-3);
  std::printf("[measured] wall impulse %.6e N s, bar's momentum change %.6e N s (%.2e)\n",
              r.impulse, dp, r.impulse / dp - 1.0);
  EXPECT_NEAR(r.impulse, dp, 1e-4 * dp);
  EXPECT_NEAR(r.wall_work, r.external, 1e-12 * r.e0);
}

// NSID 0 (every node): the same answer; a node never near the wall is never touched.
TEST(RigidWall, AllNodesGiveTheSameAnswer) {
  const WallRun a = run_bar(false), b = run_bar(true);
  EXPECT_NEAR(b.vz_end, a.vz_end, 1e-12);
  EXPECT_NEAR(b.external, a.external, 1e-12 * a.e0);
}

// The same bar and wall turned about a skew axis: the wall's normal is no coordinate axis, and
// the answer is the same (to the coordinates' 10 significant digits in the deck).
TEST(RigidWall, ATurnedWallGivesTheSameAnswer) {
  const Vec3 axis = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
  const double th = 0.7, c = std::cos(th), s = std::sin(th);
  Mat3 r{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      r[i][j] = (1.0 - c) * axis[i] * axis[j] + (i == j ? c : 0.0);
  r[0][1] -= s * axis[2];
  r[1][0] += s * axis[2];
  r[0][2] += s * axis[1];
  r[2][0] -= s * axis[1];
  r[1][2] -= s * axis[0];
  r[2][1] += s * axis[0];
  const WallRun a = run_bar(false), b = run_bar(false, r);
  std::printf(
      "[measured] turned wall: on the wall %.6e s (aligned %.6e s), rebound %.6f v "
      "(%.6f v), wall work %.6f E0 (%.6f E0), lowest node %.3e m\n",
      b.leave - b.touch, a.leave - a.touch, b.vz_end / (kV * 1e-3), a.vz_end / (kV * 1e-3),
      b.external / b.e0, a.external / a.e0, b.z_min);
  EXPECT_NEAR(b.e0, a.e0, 1e-6 * a.e0);
  EXPECT_NEAR(b.touch, a.touch, 5e-7);  // a step: 0.35 us
  EXPECT_NEAR(b.leave - b.touch, a.leave - a.touch, 5e-7);
  EXPECT_NEAR(b.vz_end, a.vz_end, 1e-3 * kV * 1e-3);
  EXPECT_NEAR(b.external, a.external, 1e-3 * a.e0);
  EXPECT_GE(b.z_min, -1e-9);  // the deck's coordinates are written to 1e-9 of their size
  EXPECT_LT(b.worst / b.e0, 0.01);
}

// The wall's force history in result.h5 (/history/rigid_walls/floor: time, force, work), in mono
// and in multi with the bar cut into two domains (the wall, NSID 0, applied in each to its own
// nodes; the gather sums them): the same impulse, and the work equals the glstat external work.
TEST(RigidWall, ForceHistoryInResultFileMonoAndMulti) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_rigid_wall_h5_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bar.k") << bar_deck(true, identity3(), true);
  std::ofstream(dir / "bar.yaml") << "model: {deck: bar.k, units: mm-t-s}\n"
                                     "controls: {history_interval: 2.0e-7}\n"
                                     "domains:\n  low: {parts: [1]}\n  high: {parts: [2]}\n";
  struct Out {
    double impulse = 0.0, work = 0.0, external = 0.0;
    std::size_t rows = 0;
  };
  auto run = [&](const std::string& mode) {
    int status = 0;
    const auto out_dir = dir / mode;
    const std::string text = testing::run_command(
        std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " + (dir / "bar.yaml").string() +
            " --mode " + mode + " --quiet --out " + out_dir.string(),
        status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
    const io::ResultReader r((out_dir / "result.h5").string());
    EXPECT_EQ(r.wall_names(), std::vector<std::string>{"floor"});
    const io::ContactHistory h = r.wall("floor");
    Out o;
    o.rows = h.size();
    // trapezoid rule over the samples (every 0.2 us; the step is 0.34 us, so every cycle)
    for (std::size_t k = 1; k < h.size(); ++k)
      o.impulse +=
          0.5 * (h.force_N[3 * k + 2] + h.force_N[3 * k - 1]) * (h.time_s[k] - h.time_s[k - 1]);
    o.work = h.energy_J.back();
    o.external = r.glstat().back().external_work_J;
    // the deck's PIDs on the parts, also in the file gathered from the domains
    const auto parts = r.mesh_parts();
    EXPECT_EQ(parts.size(), 2u);
    for (std::size_t p = 0; p < parts.size(); ++p)
      EXPECT_EQ(parts[p].id, static_cast<std::int64_t>(p + 1)) << mode;
    return o;
  };
  const Out mono = run("mono"), multi = run("multi");
  std::printf(
      "[measured] wall history: mono %zu rows, impulse %.6e N s, work %.6e J (external %.6e J); "
      "multi %zu rows, impulse %.6e N s, work %.6e J (external %.6e J)\n",
      mono.rows, mono.impulse, mono.work, mono.external, multi.rows, multi.impulse, multi.work,
      multi.external);
  ASSERT_GT(mono.rows, 100u);
  ASSERT_GT(multi.rows, 100u);
  // M (v_end + v) ~ 2 M v: 0.785 N s (7.85e-3 kg x 5 m/s x 2, less the wall's 1.6 %)
  EXPECT_NEAR(mono.impulse, 0.7787, 0.01);
  EXPECT_NEAR(multi.impulse, mono.impulse, 0.01 * mono.impulse);
  EXPECT_NEAR(mono.work, mono.external, 1e-9);
  EXPECT_NEAR(multi.work, multi.external, 0.01 * std::abs(multi.external));
  EXPECT_LT(mono.work, 0.0);
  if (!::testing::Test::HasFailure()) std::filesystem::remove_all(dir);
}

// A moving wall (*RIGIDWALL_PLANAR_MOVING, mass M = the bar's, V0 = 5 m/s) strikes the elastic bar
// at rest: Saint-Venant's impact of a mass on a long bar (Goldsmith, "Impact", 1960, sec. 3.2;
// Johnson, "Impact Strength of Materials", 1972, sec. 1.5): until the wave returns from the far
// end (2L/c), the end moves with the mass and the bar pushes on it with rho c A V, so
// M dV/dt = -rho c A V and V = V0 exp(-t/tau), tau = M / (rho c A) = L/c here. The normal momentum
// of wall and bar together is kept at every cycle (the wall's impact with the nodes is the only
// force between them).
TEST(RigidWall, MovingWallDeceleratesAsSaintVenantsMassOnABar) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_moving_wall_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = (dir / "bar.k").string();
  const double bar_mass_t = kRho * kL * kA * kA;
  std::ofstream(path) << bar_deck(false, identity3(), false, bar_mass_t);
  const model::Model m = deck::read_deck(path, {"mm-t-s", {}}).model;
  std::filesystem::remove_all(dir);
  ASSERT_EQ(m.rigid_walls.size(), 1u);
  ASSERT_TRUE(m.rigid_walls[0].moving());
  const double M = bar_mass_t * 1e3, V0 = kV * 1e-3;  // kg, m/s
  EXPECT_NEAR(m.rigid_walls[0].mass_kg, M, 1e-12);
  EXPECT_DOUBLE_EQ(m.rigid_walls[0].velocity_m_s, V0);
  const double c = std::sqrt(kE / kRho) * 1e-3, tau = kL * 1e-3 / c;  // m/s, s
  integration::Solver s(m);
  double touch = -1.0, worst_p = 0.0, worst_v = 0.0, v_at_1 = 0.0, v_at_15 = 0.0;
  double wall_ke_loss = 0.0, wall_work = 0.0;
  testing::run(s, [&](const integration::Solver& sv) {
    const double V = sv.wall_velocity_m_s(0);
    double p = M * V;
    for (std::size_t i = 0; i < m.nodes.count(); ++i)
      p += sv.mass()[i] * sv.velocity_mid()[3 * i + 2];
    worst_p = std::max(worst_p, std::abs(p - M * V0) / (M * V0));
    if (touch < 0.0 && V < V0) touch = sv.time_s();
    if (touch >= 0.0) {
      const double t = sv.time_s() - touch;
      if (t > 0.1 * tau && t < 1.9 * tau)
        worst_v = std::max(worst_v, std::abs(V - V0 * std::exp(-t / tau)) / V0);
      if (v_at_1 == 0.0 && t >= tau) v_at_1 = V / V0;
      if (v_at_15 == 0.0 && t >= 1.5 * tau) v_at_15 = V / V0;
    }
    wall_ke_loss = 0.5 * M * (V0 * V0 - V * V);
    wall_work = sv.wall_work_J(0);
  });
  std::printf(
      "[measured] moving wall (M = bar, 5 m/s) on an elastic bar: V/V0 %.4f at L/c (e^-1 = "
      "%.4f), %.4f at 1.5 L/c (%.4f); largest |V - V0 exp(-t/tau)| %.4f V0 over (0.1, 1.9) L/c; "
      "normal momentum kept to %.1e; wall's kinetic energy lost %.5f J, its work on the bar "
      "%.5f J, balance %.2e E\n",
      v_at_1, std::exp(-1.0), v_at_15, std::exp(-1.5), worst_v, worst_p, wall_ke_loss, wall_work,
      s.energy().balance_J() / wall_ke_loss);
  ASSERT_GT(touch, 0.0);
  EXPECT_LT(worst_p, 1e-12);
  EXPECT_LT(worst_v, 0.01);
  // the bar's energy is the wall's work on it; the wall lost more (the nodes' plastic impacts)
  EXPECT_GT(wall_work, 0.0);
  EXPECT_LT(wall_work, wall_ke_loss);
  EXPECT_LT(std::abs(s.energy().balance_J()), 1e-6 * wall_ke_loss);
}

// A moving wall whose nodes lie in two domains is refused before the run, with the fix.
TEST(RigidWall, MovingWallAcrossDomainsIsRefused) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_moving_wall_domains_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bar.k") << bar_deck(true, identity3(), true, kRho * kL * kA * kA);
  std::ofstream(dir / "bar.yaml") << "model: {deck: bar.k, units: mm-t-s}\n"
                                     "domains:\n  low: {parts: [1]}\n  high: {parts: [2]}\n";
  int status = 0;
  const std::string text = testing::run_command(
      std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " + (dir / "bar.yaml").string() +
          " --mode multi --quiet --out " + (dir / "out").string(),
      status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << text;
  EXPECT_NE(text.find("moving rigid wall 'floor': "), std::string::npos) << text;
  EXPECT_NE(text.find("a moving wall is computed in one domain"), std::string::npos) << text;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace crashlink
