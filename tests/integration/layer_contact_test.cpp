// Contact across domains with the `layer` scheme (docs/design.md §2.7 "Contact across subdomains"):
// the coarse side's contact-surface element layer moves into the fine domain, the contact is
// computed there at the fine step, J couples as for a permanent link. Both ways round:
//   (a) master surface on the coarse side: a fine hex block dropped on a coarse shell floor
//       (partition_models.h block_on_floor: the plate moves into "block", J on x = 0.5);
//   (b) slave nodes on the coarse side: a fine shell ball dropped on a coarse plate
//       (ball_on_ground: the 16 central plate elements move into "ball").
// `multi` (LayerNetwork, coarse step r times the fine one, r = the natural ratio and 2, 4, 8) vs
// mono at the fine step actually used: peak contact force, contact duration, impulse, rebound
// speed of the impactor (issue bounds at r <= 4: 5 %, 2 %, 0.5 % of m v0, 2 %; stable to r = 8).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

void fix(model::Model& m, const std::vector<std::int32_t>& nodes, std::uint8_t mask) {
  for (auto i : nodes) m.fixed[static_cast<std::size_t>(i)] |= mask;
}

struct Impact {
  double peak_N = 0.0, duration_s = 0.0, impulse_Ns = 0.0, rebound_m_s = 0.0;
  double m_v0 = 0.0;  ///< impactor mass x impact speed [N s]
};

/// Contact history of `s`'s contact 0 sampled every cycle: peak |F|, duration (F != 0), impulse.
struct ContactRecorder {
  Impact r;
  double t_first = -1.0, t_last = -1.0, t_prev = 0.0, fz_prev = 0.0;
  void sample(const integration::Solver& s) {
    const auto& c = s.contact_steps().at(0);
    const double f = std::hypot(c.resultant_N[0], c.resultant_N[1], c.resultant_N[2]);
    const double t = s.time_s();
    r.peak_N = std::max(r.peak_N, f);
    if (f > 0.0) {
      if (t_first < 0.0) t_first = t;
      t_last = t;
    }
    r.impulse_Ns += 0.5 * (fz_prev + c.resultant_N[2]) * (t - t_prev);  // trapezoid
    t_prev = t;
    fz_prev = c.resultant_N[2];
  }
};

/// Mass-weighted z velocity of the impactor's nodes (global indices) from their owners.
double impactor_vz(const std::vector<std::int32_t>& nodes, const std::vector<double>& mass,
                   const std::function<double(std::size_t)>& vz) {
  double mv = 0.0, mt = 0.0;
  for (auto g : nodes) {
    const auto gi = static_cast<std::size_t>(g);
    mv += mass[gi] * vz(gi);
    mt += mass[gi];
  }
  return mv / mt;
}

struct Setup {
  model::Model m;
  std::vector<std::int32_t> impactor;
  std::string fine, coarse;
  double v0 = 5.0;     ///< impact speed [m/s], -z
  double t_end = 0.0;  ///< s
};

Setup block_case() {
  Setup s{block_on_floor(), {}, "block", "floor"};
  auto& m = s.m;
  s.impactor = where(m, [](double, double, double z) { return z > 1e-4; });
  fix(m,
      where(m,
            [](double x, double y, double z) {
              return std::abs(z) < 1e-9 &&
                     (x < 1e-9 || x > 1.0 - 1e-9 || y < 1e-9 || y > 0.5 - 1e-9);
            }),
      63);
  for (auto i : s.impactor) m.initial_velocities.push_back({{i}, {0.0, 0.0, -s.v0}});
  m.controls.bulk_viscosity = true;
  s.t_end = 1.2e-3;
  m.controls.end_time_s = 10.0;
  return s;
}

Setup ball_case() {
  Setup s{ball_on_ground(), {}, "ball", "ground"};
  auto& m = s.m;
  s.impactor = where(m, [](double, double, double z) { return z > 1e-4; });
  fix(m,
      where(m,
            [](double x, double y, double z) {
              return std::abs(z) < 1e-9 && (std::abs(x) > 0.5 - 1e-9 || std::abs(y) > 0.5 - 1e-9);
            }),
      63);
  for (auto i : s.impactor) m.initial_velocities.push_back({{i}, {0.0, 0.0, -s.v0}});
  m.controls.bulk_viscosity = true;
  s.t_end = 2.0e-3;
  m.controls.end_time_s = 10.0;
  return s;
}

struct Pair {
  Impact multi, mono;
  double ratio = 0.0;
};

Pair run_case(const Setup& s, double r) {
  const auto mass = lumped_mass(s.m);
  double mt = 0.0;
  for (auto g : s.impactor) mt += mass[static_cast<std::size_t>(g)];
  cosim::LayerNetwork probe(s.m);
  const auto& d0 = probe.domains();
  std::size_t kf = 0, kc = 0;
  for (std::size_t k = 0; k < d0.solvers.size(); ++k) {
    if (d0.solvers[k]->domain_name() == s.fine) kf = k;
    if (d0.solvers[k]->domain_name() == s.coarse) kc = k;
  }
  double h0 = 0.0;
  {
    integration::Solver mono_probe(s.m, "probe");
    mono_probe.initialize();
    h0 = 0.8 * mono_probe.dt_s();
  }
  cosim::LayerNetworkOptions o;
  o.proposal_s.assign(d0.solvers.size(), 0.0);
  o.proposal_s[kf] = h0;
  if (r > 0.0) o.proposal_s[kc] = r * h0;
  o.step_safety = 0.8;
  cosim::LayerNetwork net(s.m, o);
  net.initialize();
  const auto& d = net.domains();
  const double h = net.seconds(net.plan().step[kf]);
  Pair p;
  p.ratio = static_cast<double>(net.plan().step[kc]) / static_cast<double>(net.plan().step[kf]);
  ContactRecorder rec_multi, rec_mono;
  const auto until = static_cast<coupling::Tick>(s.t_end * 1e15);
  net.run(
      [&](std::size_t k) {
        if (k == kf) rec_multi.sample(net.solver(kf));
      },
      until);
  integration::Solver mono(s.m, "mono");
  mono.initialize();
  mono.impose_step(h);
  for (;;) {
    mono.begin_cycle();
    rec_mono.sample(mono);
    if (mono.time_s() >= net.seconds(net.stepper(kf).time()) - 0.5 * h) break;
    mono.end_cycle();
    mono.impose_step(h);
  }
  p.multi = rec_multi.r;
  p.mono = rec_mono.r;
  p.multi.duration_s = rec_multi.t_last - rec_multi.t_first;
  p.mono.duration_s = rec_mono.t_last - rec_mono.t_first;
  p.multi.rebound_m_s = impactor_vz(s.impactor, mass, [&](std::size_t g) {
    return net.solver(d.owner_solver[g]).node_velocity(d.owner_local[g])[2];
  });
  p.mono.rebound_m_s =
      impactor_vz(s.impactor, mass, [&](std::size_t g) { return mono.node_velocity(g)[2]; });
  p.multi.m_v0 = p.mono.m_v0 = mt * s.v0;
  return p;
}

void check(const Setup& s, const std::string& label, double r, bool assert_accuracy) {
  const auto p = run_case(s, r);
  const double dpeak = std::abs(p.multi.peak_N / p.mono.peak_N - 1.0);
  const double ddur = std::abs(p.multi.duration_s / p.mono.duration_s - 1.0);
  const double dimp = std::abs(p.multi.impulse_Ns - p.mono.impulse_Ns) / p.mono.m_v0;
  const double dreb = std::abs(p.multi.rebound_m_s / p.mono.rebound_m_s - 1.0);
  std::printf(
      "[measured] layer contact across domains, %s, step ratio %.2f: peak force %.4g vs %.4g N "
      "(%.2f %%), duration %.4g vs %.4g ms (%.2f %%), impulse mismatch %.3f %% of m v0, impactor "
      "velocity at the end %.4g vs %.4g m/s (%.2f %%)\n",
      label.c_str(), p.ratio, p.multi.peak_N, p.mono.peak_N, 100 * dpeak, 1e3 * p.multi.duration_s,
      1e3 * p.mono.duration_s, 100 * ddur, 100 * dimp, p.multi.rebound_m_s, p.mono.rebound_m_s,
      100 * dreb);
  EXPECT_TRUE(std::isfinite(p.multi.rebound_m_s)) << label;
  EXPECT_GT(p.mono.peak_N, 0.0) << label;
  EXPECT_LT(p.multi.peak_N, 2.0 * p.mono.peak_N) << label << ": unstable?";
  if (assert_accuracy) {
    EXPECT_LE(dpeak, 0.05) << label << " r = " << p.ratio;
    EXPECT_LE(ddur, 0.02) << label << " r = " << p.ratio;
    EXPECT_LE(dimp, 0.005) << label << " r = " << p.ratio;
    EXPECT_LE(dreb, 0.02) << label << " r = " << p.ratio;
  }
}

}  // namespace

TEST(LayerContact, FineBlockOnCoarseFloorMasterOnCoarseSide) {
  const auto s = block_case();
  for (double r : {0.0, 2.0, 4.0}) check(s, "block on floor", r, true);
  check(s, "block on floor", 8.0, false);
  auto undamped = s;
  undamped.m.controls.bulk_viscosity = false;
  for (double r : {3.0, 8.0}) check(undamped, "block on floor, no bulk viscosity", r, r <= 4.0);
}

TEST(LayerContact, FineBallOnCoarseGroundSlaveOnCoarseSide) {
  const auto s = ball_case();
  for (double r : {0.0, 2.0, 4.0}) check(s, "ball on ground", r, true);
  check(s, "ball on ground", 8.0, false);
  auto undamped = s;
  undamped.m.controls.bulk_viscosity = false;
  for (double r : {3.0, 8.0}) check(undamped, "ball on ground, no bulk viscosity", r, r <= 4.0);
}
