// Issue 21's bar test (contact_bar_pair.h): a striker at v hits an equal bar at rest; 1-D theory
// gives contact for 2L/c at rho c v / 2, the striker stops and the struck bar leaves at v.
#include "tests/integration/contact_bar_pair.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "solver/core/errors.h"
#include "solver/integration/solver.h"
#include "tests/integration/run_helpers.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

struct BarPairResult {
  double duration_s = 0.0, mean_pressure_Pa = 0.0;
  double v_striker = 0.0, v_struck = 0.0;  ///< mean x velocities at the end [m/s]
  double E0 = 0.0, kinetic_end_J = 0.0, contact_end_J = 0.0, contact_min_J = 0.0;
  double total_end_J = 0.0;
  std::string stopped;  ///< the error that ended the run, empty if none
  double c = 0.0, rho = 7850.0;
};

double mean_vx(const integration::Solver& s, const std::vector<std::int32_t>& nodes) {
  double p = 0.0, mt = 0.0;
  for (auto i : nodes) {
    const auto k = static_cast<std::size_t>(i);
    p += s.mass()[k] * s.node_velocity(k)[0];
    mt += s.mass()[k];
  }
  return p / mt;
}

BarPairResult run_mono(const BarPairSpec& spec) {
  BarPair b = make_bar_pair(spec);
  BarPairResult r;
  r.c = std::sqrt(210e9 / r.rho);
  const double T = 2.0 * spec.length_m / r.c;
  if (std::getenv("CRASHLINK_NO_BULK")) b.m.controls.bulk_viscosity = false;
  b.m.controls.end_time_s = spec.gap_m / spec.speed_m_s + 1.6 * T;
  const double side = std::min(spec.side_striker_m, spec.side_struck_m);
  const double A = side * side;
  const double p_th = 0.5 * r.rho * r.c * spec.speed_m_s;
  integration::Solver s(b.m);
  double t_first = -1.0, t_last = -1.0, impulse = 0.0, t_prev = 0.0, f_prev = 0.0;
  bool first = true;
  try {
    run(s, [&](const integration::Solver& sv) {
      const auto& e = sv.energy();
      if (first) r.E0 = e.total_J(), first = false;
      const auto& cs = sv.contact_steps()[0];
      // force on the striker, -x while in contact
      const double fx = spec.slave_striker ? -cs.resultant_N[0] : cs.resultant_N[0];
      const double t = sv.time_s();
      if (std::fabs(fx) > 0.5 * p_th * A) {
        if (t_first < 0.0) t_first = t;
        t_last = t;
      }
      impulse += 0.5 * (fx + f_prev) * (t - t_prev);
      t_prev = t;
      f_prev = fx;
      r.contact_min_J = std::min(r.contact_min_J, e.contact_J);
      if (std::getenv("CRASHLINK_TRACE") && (true))
        std::printf(
            "dt %.3e t %.4e fx %.4e pot %.4e ifaceJ %.4e contactJ %.4e KE %.4e pairs %lld\n",
            sv.dt_s(), t, fx, cs.potential_J, cs.energy_J, e.contact_J, e.kinetic_J,
            static_cast<long long>(cs.active_pairs));
      r.contact_end_J = e.contact_J;
      r.kinetic_end_J = e.kinetic_J;
      r.total_end_J = e.total_J();
    });
  } catch (const std::exception& e) {
    r.stopped = e.what();
  }
  r.duration_s = t_last - t_first;
  r.mean_pressure_Pa = r.duration_s > 0.0 ? impulse / (A * r.duration_s) : 0.0;
  r.v_striker = mean_vx(s, b.striker);
  r.v_struck = mean_vx(s, b.struck);
  return r;
}

std::string describe(const BarPairSpec& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "h %.2g|%.2g mm, side %.3g|%.3g mm, slave %s, %s, %.3g deg, %.3g m/s",
                1e3 * s.h_striker_m, 1e3 * s.h_struck_m, 1e3 * s.side_striker_m,
                1e3 * s.side_struck_m, s.slave_striker ? "striker" : "struck",
                s.two_pass ? "two-pass" : "one-pass", s.misalignment_deg, s.speed_m_s);
  return buf;
}

void report(const BarPairSpec& spec, const BarPairResult& r) {
  const double T = 2.0 * spec.length_m / r.c;
  const double p_th = 0.5 * r.rho * r.c * spec.speed_m_s;
  std::printf(
      "[measured] bars (%s): duration/(2L/c) %.4f, p/(rho c v/2) %.4f, v_striker/v %.4f, "
      "v_struck/v %.4f, KE_end/E0 %.5f, contact_end/E0 %+.5f (min %+.5f), total_end/E0 %.5f%s%s\n",
      describe(spec).c_str(), r.duration_s / T, r.mean_pressure_Pa / p_th,
      r.v_striker / spec.speed_m_s, r.v_struck / spec.speed_m_s, r.kinetic_end_J / r.E0,
      r.contact_end_J / r.E0, r.contact_min_J / r.E0, r.total_end_J / r.E0,
      r.stopped.empty() ? "" : ", STOPPED: ", r.stopped.substr(0, 700).c_str());
}

}  // namespace

TEST(ContactBarPair, Explore) {
  if (!std::getenv("CRASHLINK_EXPLORE")) GTEST_SKIP() << "set CRASHLINK_EXPLORE";
  for (bool slave_striker : {true, false})
    for (bool fine_striker : {true, false}) {
      BarPairSpec s;
      s.two_pass = std::getenv("CRASHLINK_TWO_PASS") != nullptr;
      if (const char* nu = std::getenv("CRASHLINK_NU")) s.nu = std::atof(nu);
      s.slave_striker = slave_striker;
      if (!fine_striker) std::swap(s.h_striker_m, s.h_struck_m);
      report(s, run_mono(s));
    }
}
