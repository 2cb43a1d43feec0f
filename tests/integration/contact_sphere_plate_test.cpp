// Issue 21, acceptance item 4 (contact_sphere_plate.h): a rigid steel ball dropped square onto
// the centre of a clamped 1 mm steel plate must stay on its axis, run to 6 ms without the guard
// stopping it, create no contact energy, and (200 x 200) keep today's rebound, peak force and
// deflection within 1 %.
//
// Scene. The issue gives R 25 mm, 10 m/s, frictionless, a clamped 1 mm steel plate meshed
// 200 x 200 and 50 x 50, the sphere generator with 8 divisions, penalty 0.1, and today's 200 x 200
// elastic values 8.197 m/s, 4470 N, -9.90 mm, v_y -0.60 m/s; not the plate's size nor the
// sphere's mass. Tried (today's code): plate 0.1 / 0.2 / 0.3 / 0.4 / 0.5 / 0.7 m, sphere 0.062 kg
// (1 mm steel shell), 0.1, 0.25, 0.514 (solid steel ball), 0.6 kg. A 0.5 x 0.5 m plate and a
// 0.6 kg ball give at 200 x 200: rebound 8.167 m/s (-0.4 %), peak force of the loading 4428 N
// (-0.9 %), deflection -9.817 mm (-0.8 %), v_y -0.65 m/s, a contact-energy jump at 3.76 ms
// (issue: 4.58 ms) leaving -0.93 J: the scene to within 1 %, taken here. Not reproduced:
// the 50 x 50 stop (85 kN spike at 4.11 ms, 29.5 J): this 50 x 50 elastic run breaks the
// symmetry too (v_y -0.48 m/s) but runs to the end; 50 x 50 J2 shows a 19 kN spike at 2.57 ms
// creating 1.2 J.
// So: plate 0.5 x 0.5 m, 1 mm, clamped edges (all six dofs); sphere R 25 mm, cube-sphere with 8
// divisions, 1 mm contact thickness, rigid body of 0.6 kg (inertia 2/5 m R^2) at 10 m/s;
// frictionless, penalty 0.1, plate nodes against the sphere's segments (kind SurfaceToSurface, the
// scenario default); 0.1 mm gap; 6 ms; elastic steel or test_models.h j2_steel.
//
// Measured per run ([measured] line):
//   lateral   max over time of |v_x|, |v_y| and |(v_x, v_y)| of the sphere over v0 = 10 m/s (the
//             normal velocity passes through 0 at the turn, so the impact speed is the scale), and
//             at the end |(v_x, v_y)| / |v_z|; the sphere's spin |omega| R / v0 as well;
//   jumps     dE_c = the largest one-cycle change of the interface's contact energy
//             (ContactStep::energy_J) and its ratio to the running scale S = max(largest |E_c|
//             before that cycle, 1e-4 E0); and the largest one-cycle change of E_c - potential_J
//             (frictionless, E_c - potential is what the contact has created (< 0) or destroyed:
//             its change in one cycle is the jump itself, free of the stored energy's own rise);
//   rebound   v_z of the sphere at the end; the peak |contact resultant| while the sphere moves
//             down (the impact's loading; today's asymmetric spikes come later, the overall peak
//             is printed too); the plate centre's least u_z;
//   stopped   the guard's message if it stopped the run.
//
// CI runs the 50 x 50 plate (1-3 s each); the 200 x 200 plate (2-2.5 min each on one core)
// only with CRASHLINK_LONG=1:
//   CRASHLINK_LONG=1 build/tests/test_integration --gtest_filter='ContactSpherePlate.*'
//     --gtest_also_run_disabled_tests
// Each scene runs once per process: the measuring test and its DISABLED_ acceptance twin share the
// result (cached), so enabling the twin costs nothing.
#include "tests/integration/contact_sphere_plate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "solver/integration/solver.h"
#include "tests/integration/run_helpers.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

struct SpherePlateResult {
  double v0 = 0.0, E0 = 0.0;
  double lat_x_max = 0.0, lat_y_max = 0.0, lat_max = 0.0;  ///< [m/s] max over time
  double spin_max = 0.0;                                   ///< max |omega| R [m/s]
  double vx_end = 0.0, vy_end = 0.0, vz_end = 0.0;         ///< [m/s] at the end
  double peak_N = 0.0, t_peak = 0.0;              ///< largest |contact resultant| over the run
  double first_peak_N = 0.0, t_first_peak = 0.0;  ///< the same while the sphere moves down
  double deflection_m = 0.0, t_deflection = 0.0;  ///< least u_z of the plate centre, its time
  double jump_J = 0.0, t_jump = 0.0, jump_scale_J = 0.0;  ///< largest |dE_c| in one cycle
  double jump_ratio = 0.0, t_jump_ratio = 0.0;  ///< largest |dE_c| / S over the run, its time
  /// the same over the cycles where the contact is established (largest |E_c| before >= 1e-3 E0)
  double late_ratio = 0.0, t_late_ratio = 0.0;
  /// largest one-cycle change of E_c - potential (frictionless: the energy the contact creates
  /// or destroys in that cycle), its time, and the running scale S then
  double err_jump_J = 0.0, t_err_jump = 0.0, err_jump_scale_J = 0.0;
  double contact_min_J = 0.0, contact_end_J = 0.0;
  double balance_end = 0.0;  ///< energy balance error at the end (EnergyAccount)
  bool in_contact_end = true;
  std::int64_t cycles = 0;
  double t_end = 0.0, wall_s = 0.0;
  std::string stopped;
};

SpherePlateResult run_sphere_plate(const SpherePlateSpec& spec) {
  SpherePlate b = make_sphere_plate(spec);
  SpherePlateResult r;
  r.v0 = spec.speed_m_s;
  integration::Solver s(b.m);
  const auto c0 = static_cast<std::size_t>(b.centre);
  double e_prev = 0.0, err_prev = 0.0, scale = 0.0;
  bool first = true;
  const auto w0 = std::chrono::steady_clock::now();
  try {
    run(s, [&](const integration::Solver& sv) {
      const auto& e = sv.energy();
      if (first) r.E0 = e.total_J(), first = false;
      const auto& body = sv.rigid_bodies()[0];
      const Vec3 v = body.velocity;
      r.lat_x_max = std::max(r.lat_x_max, std::fabs(v[0]));
      r.lat_y_max = std::max(r.lat_y_max, std::fabs(v[1]));
      r.lat_max = std::max(r.lat_max, std::hypot(v[0], v[1]));
      r.spin_max = std::max(r.spin_max, norm(body.omega) * spec.radius_m);
      r.vx_end = v[0], r.vy_end = v[1], r.vz_end = v[2];
      const auto& cs = sv.contact_steps()[0];
      const double f = norm({cs.resultant_N[0], cs.resultant_N[1], cs.resultant_N[2]});
      if (f > r.peak_N) r.peak_N = f, r.t_peak = sv.time_s();
      if (f > r.first_peak_N && v[2] < 0.0) r.first_peak_N = f, r.t_first_peak = sv.time_s();
      r.in_contact_end = cs.active_pairs > 0;
      const double uz = sv.displacement()[3 * c0 + 2];
      if (uz < r.deflection_m) r.deflection_m = uz, r.t_deflection = sv.time_s();
      const double de = std::fabs(cs.energy_J - e_prev);
      const double S = std::max(scale, 1e-4 * r.E0);
      if (de > r.jump_J) r.jump_J = de, r.t_jump = sv.time_s(), r.jump_scale_J = S;
      if (de / S > r.jump_ratio) r.jump_ratio = de / S, r.t_jump_ratio = sv.time_s();
      if (scale >= 1e-3 * r.E0 && de / scale > r.late_ratio)
        r.late_ratio = de / scale, r.t_late_ratio = sv.time_s();
      const double err = cs.energy_J - cs.potential_J;
      if (std::fabs(err - err_prev) > r.err_jump_J)
        r.err_jump_J = std::fabs(err - err_prev), r.t_err_jump = sv.time_s(),
        r.err_jump_scale_J = S;
      err_prev = err;
      scale = std::max(scale, std::fabs(cs.energy_J));
      e_prev = cs.energy_J;
      r.contact_min_J = std::min(r.contact_min_J, cs.energy_J);
      r.contact_end_J = cs.energy_J;
      r.balance_end = e.balance_error();
      r.cycles = sv.cycle();
      r.t_end = sv.time_s();
    });
  } catch (const std::exception& e) {
    r.stopped = e.what();
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  return r;
}

std::string describe(const SpherePlateSpec& s) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%dx%d %s, plate %.3g m, ball %.3g kg", s.plate_divisions,
                s.plate_divisions, s.j2 ? "J2" : "elastic", s.plate_side_m, s.sphere_mass_kg);
  return buf;
}

void report(const SpherePlateSpec& spec, const SpherePlateResult& r) {
  const double lat_end = std::hypot(r.vx_end, r.vy_end);
  std::printf(
      "[measured] sphere on plate (%s): lateral max |vx|/v0 %.3e |vy|/v0 %.3e |v_lat|/v0 %.3e, "
      "end |v_lat|/|vz| %.3e (v %+.4f %+.4f %+.4f m/s), spin max |w|R/v0 %.3e; rebound %.4f m/s, "
      "peak force %.1f N at %.3f ms (loading %.1f N at %.3f ms), centre deflection %.3f mm "
      "at "
      "%.3f ms; contact energy: largest "
      "one-cycle change %.3e J (%.2e E0) at %.3f ms against a running scale %.3e J, largest "
      "change/scale %.3g at %.3f ms (established contact %.3g at %.3f ms); largest one-cycle "
      "change of E_c - potential %.3e J (%.2e E0, "
      "%.3g S) at %.3f ms; min %.4e J, end %.4e J (%.2e E0); balance %.2e; E0 %.4f J; "
      "%s at %.3f ms, %lld cycles, %.1f s%s%s\n",
      describe(spec).c_str(), r.lat_x_max / r.v0, r.lat_y_max / r.v0, r.lat_max / r.v0,
      lat_end / std::max(std::fabs(r.vz_end), 1e-30), r.vx_end, r.vy_end, r.vz_end,
      r.spin_max / r.v0, r.vz_end, r.peak_N, 1e3 * r.t_peak, r.first_peak_N, 1e3 * r.t_first_peak,
      1e3 * r.deflection_m, 1e3 * r.t_deflection, r.jump_J, r.jump_J / r.E0, 1e3 * r.t_jump,
      r.jump_scale_J, r.jump_ratio, 1e3 * r.t_jump_ratio, r.late_ratio, 1e3 * r.t_late_ratio,
      r.err_jump_J, r.err_jump_J / r.E0, r.err_jump_J / r.err_jump_scale_J, 1e3 * r.t_err_jump,
      r.contact_min_J, r.contact_end_J, r.contact_end_J / r.E0, r.balance_end, r.E0,
      r.in_contact_end ? "in contact" : "separated", 1e3 * r.t_end,
      static_cast<long long>(r.cycles), r.wall_s,
      r.stopped.empty() ? "" : ", STOPPED: ", r.stopped.substr(0, 300).c_str());
  std::fflush(stdout);
}

SpherePlateSpec variant(int divisions, bool j2) {
  SpherePlateSpec s;  // the defaults are this scene (0.5 m plate, 0.6 kg ball)
  s.plate_divisions = divisions;
  s.j2 = j2;
  return s;
}

/// The scene's result, run once per process (the measuring test and its acceptance twin).
const SpherePlateResult& result_of(int divisions, bool j2) {
  static std::map<std::pair<int, bool>, SpherePlateResult> cache;
  const auto key = std::make_pair(divisions, j2);
  auto it = cache.find(key);
  if (it == cache.end()) {
    const auto spec = variant(divisions, j2);
    it = cache.emplace(key, run_sphere_plate(spec)).first;
    report(spec, it->second);
  }
  return it->second;
}

bool long_runs() {
  const char* v = std::getenv("CRASHLINK_LONG");
  return v && std::string(v) != "0";
}

/// Today's values at 200 x 200 (HEAD 641078a, one-pass node-to-segment contact), the reference
/// of "unchanged within 1 %": rebound, peak force of the loading, least centre deflection.
/// Caution: today's runs include the energy their contact created (contact energy at the end
/// -0.93 J elastic, -0.22 J J2, against E0 = 30 J); given wholly to the ball, 0.93 J is 2.3 % of
/// its rebound speed, so a contact that creates nothing may land outside 1 % of today's rebound for
/// that reason alone. The J2 peak (5057 N at 2.074 ms) coincides with a contact-energy event
/// (E_c - potential moves by 0.037 J at 2.078 ms): it may not be the impact's own peak either.
struct Today {
  double rebound_m_s, peak_N, deflection_m;
};
constexpr Today kToday200Elastic{8.1667, 4428.4, -9.817e-3};  // issue: 8.197, 4470, -9.90e-3
constexpr Today kToday200J2{5.0869, 5056.8, -13.413e-3};

/// Acceptance item 4.
///   lateral  below 1e-6 of the normal velocity: max over time |v_lat| < 1e-6 v0 (the normal
///            velocity passes through 0 at the turn) and at the end |v_lat| < 1e-6 |v_z| (the
///            issue's bound; an established code keeps this impact symmetric to 1e-12, so 1e-6
///            leaves round-off six orders of room);
///   jumps    no cycle changes E_c - potential (the energy the frictionless contact creates or
///            destroys) by 1e-3 E0 = 0.03 J or more: a pair that closes within a step books up to
///            1/2 k (v0 dt)^2 there (today 2.1e-3 J = 7e-5 E0 at the first contact, 50 x 50; a
///            soft stiffness of 0.1 m/dt^2 would give 0.05 m v0^2 = 4e-3 J per 50 x 50 plate node),
///            today's jumps are 0.66 J (200 elastic), 0.037 J (200 J2), 1.23 J (50 J2). The ratio
///            of a cycle's change of E_c to the largest E_c before it (printed) is not asserted:
///            the first cycles of contact on the 50 x 50 mesh take it to 3.5 (0.3 once E_c has
///            passed 1e-3 E0) with no defect, and today's 200 x 200 elastic jump gives only 0.52;
///   energy   contact energy >= -1e-3 E0 at every cycle (the head impact's bound in the issue;
///            today -3.1e-2 E0 elastic 200, -7.3e-3 E0 J2 200, -4.1e-2 E0 J2 50).
void expect_acceptance(const SpherePlateResult& r, const Today* today) {
  EXPECT_TRUE(r.stopped.empty()) << r.stopped;
  EXPECT_GE(r.t_end, 6e-3 * (1.0 - 1e-9));
  EXPECT_LT(r.lat_max, 1e-6 * r.v0) << "max |v_lat| " << r.lat_max << " m/s";
  EXPECT_LT(std::hypot(r.vx_end, r.vy_end), 1e-6 * std::fabs(r.vz_end));
  EXPECT_LT(r.err_jump_J, 1e-3 * r.E0) << "contact energy jump at " << r.t_err_jump << " s";
  EXPECT_GE(r.contact_min_J, -1e-3 * r.E0);
  if (today) {  // 1 %: the bound
    EXPECT_NEAR(r.vz_end, today->rebound_m_s, 0.01 * std::fabs(today->rebound_m_s));
    EXPECT_NEAR(r.first_peak_N, today->peak_N, 0.01 * today->peak_N);
    EXPECT_NEAR(r.deflection_m, today->deflection_m, 0.01 * std::fabs(today->deflection_m));
  }
}

}  // namespace

// ---- 50 x 50: CI ----

/// The symmetry of item 4 (lateral velocity below 1e-6 of the normal one), asserted in CI. It
/// broke about y = 0 only (|v_y| 9.4e-5 v0 elastic, 1.8e-4 v0 J2; |v_x| 1e-13): the shell frame
/// followed edge 1-2, which the plate generator lays along +x, so the mirror image about y = 0 of
/// an element starts at another edge and its stresses were carried by another rotation. With the
/// frame on the diagonals (shell_bt_forces.cpp) both stay below 1e-12 v0.
void expect_symmetric(const SpherePlateResult& r) {
  EXPECT_LT(r.lat_max, 1e-6 * r.v0) << "max |v_x| " << r.lat_x_max << ", |v_y| " << r.lat_y_max;
  EXPECT_LT(std::hypot(r.vx_end, r.vy_end), 1e-6 * std::fabs(r.vz_end));
}

TEST(ContactSpherePlate, Elastic50Measured) {
  const auto& r = result_of(50, false);
  EXPECT_GT(r.peak_N, 0.0);
  expect_symmetric(r);
}

// Passes since the shell frame is numbering-invariant (lateral 9e-14 v0); before: lateral
// 9.4e-5 v0, the rest passed (no stop, contact energy >= 0).
TEST(ContactSpherePlate, Elastic50Acceptance) {
  expect_acceptance(result_of(50, false), nullptr);
}

TEST(ContactSpherePlate, J2_50Measured) {
  const auto& r = result_of(50, true);
  EXPECT_GT(r.peak_N, 0.0);
  expect_symmetric(r);
}

// Passes since the shell frame is numbering-invariant (lateral 3e-13 v0); before: lateral
// 1.8e-4 v0, the rest passed.
TEST(ContactSpherePlate, J2_50Acceptance) {
  expect_acceptance(result_of(50, true), nullptr);
}

// ---- 200 x 200: CRASHLINK_LONG=1 ----

TEST(ContactSpherePlate, Elastic200Measured) {
  if (!long_runs()) GTEST_SKIP() << "200 x 200 (about 2 min): set CRASHLINK_LONG=1";
  const auto& r = result_of(200, false);
  EXPECT_GT(r.peak_N, 0.0);
}

// Today: lateral 6.6e-2 v0 (v_y -0.65 m/s at the end); an 8.7 kN spike at 3.76 ms, E_c - potential
// moves by 0.66 J in one cycle, contact energy ends at -0.93 J (-3.1e-2 E0); no stop; the 1 %
// values are today's own.
TEST(ContactSpherePlate, Elastic200Acceptance) {
  if (!long_runs()) GTEST_SKIP() << "200 x 200 (about 2 min): set CRASHLINK_LONG=1";
  expect_acceptance(result_of(200, false), &kToday200Elastic);
}

TEST(ContactSpherePlate, J2_200Measured) {
  if (!long_runs()) GTEST_SKIP() << "200 x 200 (about 2 min): set CRASHLINK_LONG=1";
  const auto& r = result_of(200, true);
  EXPECT_GT(r.peak_N, 0.0);
}

// Today: lateral 4.1e-2 v0 (v_x = v_y = +0.117 m/s at the end, the diagonal the issue saw);
// E_c - potential moves by 0.037 J (1.2e-3 E0) in one cycle at 2.08 ms, contact energy ends at
// -0.22 J (-7.3e-3 E0); no stop. The 1 % values are the elastic run's; today's J2 peak
// (5057 N) is the spike of that contact-energy event, not the impact's, so J2 is held to the
// rest of the item (symmetry, no jump, no negative contact energy, 6 ms) and its figures are
// printed beside today's (measured: lateral 4e-15 v0, rebound 5.1315 m/s against 5.0869,
// loading peak 3502.8 N against the spike's 5056.8 N, deflection -13.431 mm against -13.413).
TEST(ContactSpherePlate, J2_200Acceptance) {
  if (!long_runs()) GTEST_SKIP() << "200 x 200 (about 2 min): set CRASHLINK_LONG=1";
  const auto& r = result_of(200, true);
  std::printf(
      "[measured] J2 200 x 200 against today: rebound %.4f m/s (%.4f), peak of the loading "
      "%.1f N (%.1f), deflection %.3f mm (%.3f)\n",
      r.vz_end, kToday200J2.rebound_m_s, r.first_peak_N, kToday200J2.peak_N, 1e3 * r.deflection_m,
      1e3 * kToday200J2.deflection_m);
  expect_acceptance(r, nullptr);
}

// The energy balance of the elastic scene is second order in the step: at dt_scale 0.45 it is
// at most a third of that at 0.9. 16 x 16 over 3 ms (0.2 s to run): -2.4e-5 and -4.5e-6 of E0,
// ratio 5.3 (50 x 50 over 6 ms: -3.1e-6 and -7.3e-7, ratio 4.3). While the shell took its velocity
// strains on x^{n+1} (shell_bt_forces.cpp) it was first order and large: 2.26e-2 and 1.03e-2,
// ratio 2.2 (50 x 50: 2.75e-2 and 1.36e-2).
TEST(ContactSpherePlate, ElasticBalanceSecondOrderInTheStep) {
  SpherePlateSpec s;
  s.plate_divisions = 16;
  s.end_time_s = 3e-3;
  double b[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    s.dt_scale = i == 0 ? 0.9 : 0.45;
    const SpherePlateResult r = run_sphere_plate(s);
    ASSERT_TRUE(r.stopped.empty()) << r.stopped;
    b[i] = r.balance_end;
  }
  std::printf("[measured] 16 x 16 elastic: balance %.3e (dt_scale 0.9), %.3e (0.45), ratio %.2f\n",
              b[0], b[1], b[0] / b[1]);
  EXPECT_LT(std::fabs(b[0]), 1e-4);
  EXPECT_GE(std::fabs(b[0]), 3.0 * std::fabs(b[1]));
}

/// Calibration: CRASHLINK_SPHERE="side div mass ts j2 end_ms [dt_scale]" runs one scene and
/// prints it (mass 0: the sphere elements' own, 4 pi R^2 ts 7850 kg/m^3; dt_scale 0.9 if absent).
TEST(ContactSpherePlate, Explore) {
  const char* v = std::getenv("CRASHLINK_SPHERE");
  if (!v) GTEST_SKIP() << "set CRASHLINK_SPHERE='side div mass ts j2 end_ms'";
  SpherePlateSpec s;
  int j2 = 0;
  double end_ms = 6.0;
  std::sscanf(v, "%lf %d %lf %lf %d %lf %lf", &s.plate_side_m, &s.plate_divisions,
              &s.sphere_mass_kg, &s.sphere_thickness_m, &j2, &end_ms, &s.dt_scale);
  s.j2 = j2 != 0;
  s.end_time_s = 1e-3 * end_ms;
  report(s, run_sphere_plate(s));
}
