// Two identical elastic bars (one row of hexes, nu = 0, so the 1-D wave speed c = sqrt(E/rho)
// is exact) meet head-on at +v and -v. 1-D elastic impact theory (e.g. Graff, Wave Motion in
// Elastic Solids, 2.1): contact pressure rho c v, contact duration 2L/c, the bars exchange their
// velocities and separate with no energy lost. Bulk viscosity is off: it would dissipate energy
// at the wave fronts (a few %), which is not what these tests measure. Default penalty scale 0.1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

constexpr double kL = 0.1, kA = 1e-3, kV = 1.0;  // bar length, side [m], impact speed [m/s]
constexpr int kN = 100;                          // elements per bar

struct BarImpact {
  double E0 = 0.0;  // initial total energy [J]
  double t_first = -1.0, t_last = -1.0;
  std::vector<double> t, pressure;  // contact pressure on the slave bar's end [Pa]
  double contact_peak_J = 0.0, contact_end_J = 0.0, total_end_J = 0.0;
  double v_left_end = 0.0, v_right_end = 0.0;
  double c = 0.0, rho = 0.0;
};

BarImpact run_bars() {
  model::Model m;
  m.name = "bars";
  m.materials.push_back(steel(0.0));
  model::Part p;
  p.material = 0;
  p.name = "left";
  model::generate_bar(m, p, {{0.0, 0.0, 0.0}, 0, kL, {kA, kA}, kN, {1, 1}});
  const std::size_t n_left = m.nodes.count();
  p.name = "right";
  model::generate_bar(m, p, {{kL, 0.0, 0.0}, 0, kL, {kA, kA}, kN, {1, 1}});  // touching at x = L
  m.fixed.assign(m.nodes.count(), 0);
  model::InitialVelocity left, right;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    (i < n_left ? left : right).nodes.push_back(static_cast<std::int32_t>(i));
  left.velocity_m_s = {kV, 0.0, 0.0};
  right.velocity_m_s = {-kV, 0.0, 0.0};
  m.initial_velocities = {left, right};
  model::Contact c;
  c.name = "bars";
  c.slave_nodes = left.nodes;
  c.master_parts = {1};
  m.contacts.push_back(c);
  m.controls.bulk_viscosity = false;
  BarImpact r;
  r.rho = 7850.0;
  r.c = std::sqrt(210e9 / r.rho);
  m.controls.end_time_s = 3.0 * kL / r.c;  // contact ends at 2L/c, then free flight
  integration::Solver s(m);
  bool first = true;
  run(s, [&](const integration::Solver& sv) {
    const auto& e = sv.energy();
    if (first) r.E0 = e.total_J(), first = false;
    const auto& cs = sv.contact_steps()[0];
    if (cs.active_pairs > 0) {
      if (r.t_first < 0.0) r.t_first = sv.time_s();
      r.t_last = sv.time_s();
    }
    r.t.push_back(sv.time_s());
    r.pressure.push_back(-cs.resultant_N[0] / (kA * kA));
    r.contact_peak_J = std::max(r.contact_peak_J, e.contact_J);
    r.contact_end_J = e.contact_J;
    r.total_end_J = e.total_J();
  });
  double p_left = 0.0, m_left = 0.0, p_right = 0.0, m_right = 0.0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double mi = s.mass()[i], vi = s.node_velocity(i)[0];
    (i < n_left ? p_left : p_right) += mi * vi;
    (i < n_left ? m_left : m_right) += mi;
  }
  r.v_left_end = p_left / m_left;
  r.v_right_end = p_right / m_right;
  return r;
}

const BarImpact& bars() {
  static const BarImpact r = run_bars();
  return r;
}

}  // namespace

TEST(ContactBars, DurationPressureVelocitySwapEnergy) {
  const BarImpact& r = bars();
  const double T = 2.0 * kL / r.c;
  // Contact starts at the first step (touching, approaching) and lasts 2L/c: 3 %.
  ASSERT_GE(r.t_first, 0.0);
  const double duration = r.t_last - r.t_first;
  EXPECT_NEAR(duration, T, 0.03 * T) << "contact lasted " << duration << " s, 2L/c = " << T;
  // Pressure plateau: median over the middle half of the contact, rho c v within 3 %.
  std::vector<double> mid;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] > r.t_first + 0.25 * T && r.t[i] < r.t_first + 0.75 * T)
      mid.push_back(r.pressure[i]);
  ASSERT_FALSE(mid.empty());
  std::nth_element(mid.begin(), mid.begin() + static_cast<std::ptrdiff_t>(mid.size() / 2),
                   mid.end());
  const double p = mid[mid.size() / 2], p_th = r.rho * r.c * kV;
  EXPECT_NEAR(p, p_th, 0.03 * p_th) << "pressure " << p << " Pa, rho c v = " << p_th;
  // Velocities swap: each bar leaves with the other's velocity (mean over the bar), 3 %.
  EXPECT_NEAR(r.v_left_end, -kV, 0.03 * kV);
  EXPECT_NEAR(r.v_right_end, kV, 0.03 * kV);
  // Energy conserved within 1 % (no viscosity; the penalty spring gives its energy back).
  EXPECT_NEAR(r.total_end_J, r.E0, 0.01 * r.E0);
  RecordProperty("duration_ratio", std::to_string(duration / T));
  RecordProperty("pressure_ratio", std::to_string(p / p_th));
  std::printf(
      "bars: duration/(2L/c) = %.4f, p/(rho c v) = %.4f, v_left = %.4f, v_right = %.4f, "
      "E_end/E0 = %.5f\n",
      duration / T, p / p_th, r.v_left_end, r.v_right_end, r.total_end_J / r.E0);
}

TEST(ContactBars, FrictionlessContactEnergyReturns) {
  // Contact energy = minus the work of the contact forces: a frictionless penalty spring gives
  // back what it stored. What remains after separation is the trapezoid rule's error when a
  // spring engages or lets go between two steps (1/2 k g^n |g^{n+1}| per node, of either sign):
  // 2.6 % of the peak here with issue 21's stiffer springs (two passes, k_soft), -0.05 % of E0
  // (issue 21 allows 0.5 % of E0); it stays below 5 % of the peak and 0.5 % of E0.
  const BarImpact& r = bars();
  ASSERT_GT(r.contact_peak_J, 0.0);
  EXPECT_LT(std::fabs(r.contact_end_J), 0.005 * r.E0);
  EXPECT_LT(std::fabs(r.contact_end_J), 0.05 * r.contact_peak_J)
      << "peak " << r.contact_peak_J << " J, after separation " << r.contact_end_J << " J";
  std::printf("bars: contact energy peak %.4e J, after separation %.4e J (%.3f %%)\n",
              r.contact_peak_J, r.contact_end_J,
              100.0 * std::fabs(r.contact_end_J) / r.contact_peak_J);
}
