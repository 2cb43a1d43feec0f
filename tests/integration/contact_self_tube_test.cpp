// Issue 21, acceptance item 2 (contact_tube.h): a square steel tube 50 x 50 x 1.5 mm, 200 mm
// long, J2, clamped at one end, crushed axially by a 50 kg rigid ram at 10 m/s, with a
// single-surface (self) contact over the tube and a ram contact. It must fold without its walls
// passing through each other:
//   penetration   the largest t - d over every tube node and every tube segment that is neither
//                 its own nor a neighbour (contact_tube.h SelfPenetrationChecker), sampled every
//                 0.1 t / (2 v0) of time (7.5 us: walls close at up to about twice the ram's speed,
//                 so no node can cross a wall between two samples unseen) < t / 2 (the issue);
//   contact energy  of each interface at every cycle >= -1e-4 E0: the issue asks >= 0; the
//                 trapezoid rule books a pair that closes or opens within a step with an error
//                 O(k g v dt) of either sign, so exact zero is not a bound a correct penalty
//                 contact meets; 1e-4 E0 is a tenth of the head impact's -0.1 % bound;
//   balance       |E - E0 - W| / E0 <= 1 % at every sample (the issue);
//   crush force   mean = (ram kinetic energy lost) / (ram travel), stated against the
//                 superfolding estimate of Wierzbicki & Abramowicz for a square tube,
//                   P_m = 9.56 sigma_0 t^(5/3) C^(1/3)
//                 (Abramowicz & Jones, "Dynamic axial crushing of square tubes", Int. J. Impact
//                 Eng. 2 (1984) 179-208, from Wierzbicki & Abramowicz, "On the crushing mechanics
//                 of thin-walled structures", J. Appl. Mech. 50 (1983) 727-734; M_0 = sigma_0
//                 t^2 / 4), sigma_0 = the mean of yield (200 MPa) and ultimate (400 MPa) of
//                 test_models.h j2_steel: 300 MPa, C = 50 mm, t = 1.5 mm: P_m = 20.8 kN. The
//                 material has no strain-rate effect; the first fold's peak weighs in a short run.
//                 The long runs check 0.5 P_m < mean < 2 P_m, a sanity range, not a precision
//                 check: the estimate's own spread against tests is about +-20 %, it ignores
//                 inertia, and sigma_0 is a convention (today's code without self-contact gives
//                 1.40 P_m over 86 mm, 1.80 P_m over the CI run's first 27 mm, the first fold's
//                 peak included).
//
// The tube's single-surface contact (model::ContactKind::SingleSurface, master_parts = the tube,
// no slave nodes); ContactSelfTube.WithoutSelfContact* run the same scene without it (the ram
// contact only), for comparison: there the walls pass through each other.
//
// Mesh: 5 mm around; 5 mm along the coarse part, 2 mm along the 60 mm fine part at the struck end
// (stable steps 2.5 x apart); multi: the two parts in two domains ("coarse", "fine" with the ram),
// in process (cosim::LayerNetwork, variable steps, step safety 0.9 as `crashlink run`).
// CI: 3 ms of crush (30 mm, the first lobe); CRASHLINK_LONG=1: 2.5 mm around and coarse, 1 mm
// fine over 100 mm, 16 ms (today without self-contact: 86 mm of crush, the ram nearly stopped;
// 7.5 min mono on one core). With it, mono (a3ca83d: a node squeezed between two layers of a
// fold gets both walls' springs): largest penetration 0.085 t, contact energy never below 0
// (self 16.5 J at the end), balance max 4.0e-5 E0, crush 80.3 mm, ram 0.15 m/s at 16 ms, mean
// force 31.1 kN = 1.50 P_m; 185434 cycles, 24 min on a loaded machine. Before, the self contact
// created 124 J (4.9 % E0) by 2.54 ms and the energy guard stopped the run.
// CRASHLINK_TUBE_PROGRESS_MS = p (mono): a line of the numbers so far every p ms.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "core/errors.h"
#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "tests/integration/contact_tube.h"
#include "tests/integration/run_helpers.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

constexpr double kSigma0 = 300e6;  // [Pa] (200 + 400) / 2, j2_steel

double superfolding_force(const TubeSpec& s) {
  return 9.56 * kSigma0 * std::pow(s.thickness_m, 5.0 / 3.0) * std::cbrt(s.width_m);
}

struct TubeResult {
  double E0 = 0.0;
  double pen_max_m = -1.0, t_pen = 0.0;
  double pen_initial_m = 0.0;  ///< at t = 0: < 0 (-t: no node within t of a segment it may touch)
  std::size_t pen_pairs_max = 0;
  int samples = 0;
  std::map<std::string, double> contact_min_J;  ///< per interface, min over every cycle
  std::map<std::string, double> contact_end_J;
  double balance_max = 0.0, balance_end = 0.0;  ///< |balance_J| / E0
  double crush_m = 0.0, v_end = 0.0, mean_force_N = 0.0, peak_force_N = 0.0;
  std::string cycles;
  double t_end = 0.0, wall_s = 0.0, check_s = 0.0;
  std::string stopped;
};

/// What every run samples: the interfaces' contact energies, the ram, the balance; the
/// penetration every `sample_dt`.
struct Sampler {
  const Tube& tube;
  const TubeSpec& spec;
  SelfPenetrationChecker checker;
  double sample_dt, next_sample = 0.0, ke0_ram = 0.0;
  TubeResult& r;
  Sampler(const Tube& t, const TubeSpec& s, TubeResult& res)
      : tube(t),
        spec(s),
        checker(t.m, t.tube_parts, s.thickness_m),
        sample_dt(0.1 * s.thickness_m / (2.0 * s.ram_speed_m_s)),
        r(res) {
    ke0_ram = 0.5 * s.ram_mass_kg * s.ram_speed_m_s * s.ram_speed_m_s;
  }
  void contacts(const integration::Solver& sv) {
    const auto& cs = sv.contact_steps();
    for (std::size_t k = 0; k < cs.size(); ++k) {
      const std::string& name = sv.model().contacts[k].name;
      auto it = r.contact_min_J.find(name);
      if (it == r.contact_min_J.end()) it = r.contact_min_J.emplace(name, 0.0).first;
      it->second = std::min(it->second, cs[k].energy_J);
      r.contact_end_J[name] = cs[k].energy_J;
      if (name == "ram")
        r.peak_force_N =
            std::max(r.peak_force_N,
                     std::hypot(cs[k].resultant_N[0], cs[k].resultant_N[1], cs[k].resultant_N[2]));
    }
  }
  void ram(const integration::Solver& sv) {
    for (const auto& b : sv.rigid_bodies()) {
      r.crush_m = b.centre0[2] - b.centre[2];
      r.v_end = b.velocity[2];
      const double ke = 0.5 * b.mass_kg * dot(b.velocity, b.velocity);
      r.mean_force_N = r.crush_m > 0.0 ? (ke0_ram - ke) / r.crush_m : 0.0;
    }
  }
  void balance(const integration::EnergyAccount& e) {
    if (r.E0 == 0.0) r.E0 = e.total_J();
    const double b = std::fabs(e.balance_J()) / r.E0;
    r.balance_max = std::max(r.balance_max, b);
    r.balance_end = b;
  }
  bool due(double t) const { return t >= next_sample; }
  void penetration(double t, const std::vector<double>& u) {
    const auto c0 = std::chrono::steady_clock::now();
    std::vector<double> x(tube.m.nodes.x0);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += u[i];
    const auto p = checker.check(x.data());
    if (r.samples == 0) r.pen_initial_m = p.penetration_m;
    if (p.penetration_m > r.pen_max_m) r.pen_max_m = p.penetration_m, r.t_pen = t;
    r.pen_pairs_max = std::max(r.pen_pairs_max, p.pairs);
    ++r.samples;
    next_sample = t + sample_dt;
    r.check_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
  }
};

/// CRASHLINK_TUBE_PROGRESS_MS = p: a line of the numbers so far every p ms of simulated time
/// (a long run's partial answer).
void progress(const TubeSpec& spec, const TubeResult& r) {
  static const double every_s = [] {
    const char* v = std::getenv("CRASHLINK_TUBE_PROGRESS_MS");
    return v ? 1e-3 * std::atof(v) : 0.0;
  }();
  static double next_s = 0.0;
  if (!(every_s > 0.0) || r.t_end < next_s) return;
  next_s = r.t_end + every_s;
  double contact_min = 0.0;
  for (const auto& [name, e] : r.contact_min_J) contact_min = std::min(contact_min, e);
  std::printf(
      "[progress] t %.3f ms: largest penetration %.3f t (at %.3f ms), contact energy min %.2e "
      "E0, balance max %.2e, crush %.2f mm, mean force %.3f P_m\n",
      1e3 * r.t_end, r.pen_max_m / spec.thickness_m, 1e3 * r.t_pen,
      r.E0 > 0.0 ? contact_min / r.E0 : 0.0, r.balance_max, 1e3 * r.crush_m,
      r.mean_force_N / superfolding_force(spec));
  std::fflush(stdout);
}

TubeResult run_mono(const TubeSpec& spec) {
  TubeResult r;
  const Tube tube = make_tube(spec);
  const auto w0 = std::chrono::steady_clock::now();
  std::unique_ptr<integration::Solver> s;
  s = std::make_unique<integration::Solver>(tube.m);
  s->initialize();
  Sampler smp(tube, spec, r);
  try {
    for (;;) {
      s->begin_cycle();
      smp.contacts(*s);
      smp.ram(*s);
      smp.balance(s->energy());
      if (smp.due(s->time_s())) smp.penetration(s->time_s(), s->displacement());
      r.t_end = s->time_s();
      progress(spec, r);
      if (s->finished()) break;
      s->end_cycle();
    }
  } catch (const std::exception& e) {
    r.stopped = e.what();
  }
  r.cycles = std::to_string(s->cycle());
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  return r;
}

TubeResult run_multi(const TubeSpec& spec) {
  TubeResult r;
  const Tube tube = make_tube(spec);
  const auto w0 = std::chrono::steady_clock::now();
  cosim::LayerNetworkOptions o;
  o.run.variable_steps = true;
  o.step_safety = 0.9;
  std::unique_ptr<cosim::LayerNetwork> net;
  net = std::make_unique<cosim::LayerNetwork>(tube.m, o);
  net->initialize();
  Sampler smp(tube, spec, r);
  std::size_t k_fine = 0;
  for (std::size_t k = 0; k < net->size(); ++k)
    if (net->solver(k).domain_name() == "fine") k_fine = k;
  try {
    net->run([&](std::size_t k) {
      const auto& sv = net->solver(k);
      smp.contacts(sv);
      if (k != k_fine) return;
      smp.ram(sv);
      // each domain's account at its own instant (the coarse one at most one coarse step apart)
      smp.balance(net->energy());
      const double t = net->seconds(net->stepper(k).time());
      if (smp.due(t)) smp.penetration(t, net->global_displacement());
      r.t_end = t;
    });
  } catch (const std::exception& e) {
    r.stopped = e.what();
  }
  for (std::size_t k = 0; k < net->size(); ++k)
    r.cycles += (k ? ", " : "") + net->solver(k).domain_name() + " " +
                std::to_string(net->solver(k).cycle());
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  return r;
}

void report(const char* label, const TubeSpec& spec, const TubeResult& r) {
  const double pm = superfolding_force(spec);
  std::string energies;
  for (const auto& [name, e] : r.contact_min_J) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s min %.3e J (%.2e E0) end %.3e J (%.2e E0); ", name.c_str(),
                  e, e / r.E0, r.contact_end_J.at(name), r.contact_end_J.at(name) / r.E0);
    energies += buf;
  }
  std::printf(
      "[measured] tube crush %s: largest penetration %.3e m = %.3f t (at %.3f ms; %d samples, at "
      "t = 0 %.3f t, "
      "most pairs within t %zu); contact energy: %sbalance max %.3e end %.3e of E0 %.1f J; "
      "crush %.2f mm, ram v_end %.3f m/s, mean force %.0f N = %.3f P_m (P_m %.0f N), peak ram "
      "force %.0f N; %.3f ms, cycles %s, %.1f s (penetration checks %.1f s)%s%s\n",
      label, r.pen_max_m, r.pen_max_m / spec.thickness_m, 1e3 * r.t_pen, r.samples,
      r.pen_initial_m / spec.thickness_m, r.pen_pairs_max, energies.c_str(), r.balance_max,
      r.balance_end, r.E0, 1e3 * r.crush_m, r.v_end, r.mean_force_N, r.mean_force_N / pm, pm,
      r.peak_force_N, 1e3 * r.t_end, r.cycles.c_str(), r.wall_s, r.check_s,
      r.stopped.empty() ? "" : ", STOPPED: ", r.stopped.substr(0, 300).c_str());
  std::fflush(stdout);
}

void expect_acceptance(const TubeSpec& spec, const TubeResult& r, bool check_force) {
  EXPECT_TRUE(r.stopped.empty()) << r.stopped;
  EXPECT_LT(r.pen_initial_m, 0.0);  // the checker sees no contact in the straight tube
  EXPECT_GE(r.t_end, spec.end_time_s * (1.0 - 1e-9));
  EXPECT_GT(r.crush_m, 0.5 * spec.ram_speed_m_s * std::min(spec.end_time_s, 3e-3));
  EXPECT_LT(r.pen_max_m, 0.5 * spec.thickness_m) << "at " << r.t_pen << " s";
  for (const auto& [name, e] : r.contact_min_J) EXPECT_GE(e, -1e-4 * r.E0) << name;
  EXPECT_LE(r.balance_max, 0.01);
  if (check_force) {
    const double pm = superfolding_force(spec);
    EXPECT_GT(r.mean_force_N, 0.5 * pm);
    EXPECT_LT(r.mean_force_N, 2.0 * pm);
  }
}

TubeSpec ci_spec() {
  return TubeSpec{};
}

TubeSpec long_spec() {
  TubeSpec s;
  s.h_around_m = 2.5e-3;
  s.h_axial_m = 2.5e-3;
  s.fine_length_m = 0.1;
  s.h_fine_m = 1e-3;
  s.end_time_s = 16e-3;
  return s;
}

bool long_runs() {
  const char* v = std::getenv("CRASHLINK_LONG");
  return v && std::string(v) != "0";
}

void crush(TubeSpec spec, bool multi, const char* label, bool check_force) {
  spec.domains = multi;
  const TubeResult r = multi ? run_multi(spec) : run_mono(spec);
  report(label, spec, r);
  expect_acceptance(spec, r, check_force);
}

}  // namespace

TEST(ContactSelfTube, CrushMono) {
  crush(ci_spec(), false, "mono (CI mesh, 3 ms)", false);
}

TEST(ContactSelfTube, CrushMulti) {
  crush(ci_spec(), true, "multi (CI mesh, 3 ms)", false);
}

TEST(ContactSelfTube, CrushMonoLong) {
  if (!long_runs()) GTEST_SKIP() << "long crush (minutes): set CRASHLINK_LONG=1";
  crush(long_spec(), false, "mono (fine mesh, 16 ms)", true);
}

TEST(ContactSelfTube, CrushMultiLong) {
  if (!long_runs()) GTEST_SKIP() << "long crush (minutes): set CRASHLINK_LONG=1";
  crush(long_spec(), true, "multi (fine mesh, 16 ms)", true);
}

// Today's code on the same scene without self-contact (the ram contact only), mono and multi:
// what the acceptance is measured against, and a check that the scene itself runs (the multi cut,
// the ram contact in the fine domain). Only that the ram crushed the tube is checked.
void without_self_contact(TubeSpec spec, bool multi, const char* label) {
  spec.self_contact = false;
  spec.domains = multi;
  const TubeResult r = multi ? run_multi(spec) : run_mono(spec);
  report(label, spec, r);
  EXPECT_TRUE(r.stopped.empty()) << r.stopped;
  EXPECT_LT(r.pen_initial_m, 0.0);  // the checker sees no contact in the straight tube
  EXPECT_GT(r.crush_m, 0.5 * spec.ram_speed_m_s * std::min(spec.end_time_s, 3e-3));
}

TEST(ContactSelfTube, WithoutSelfContactMono) {
  without_self_contact(ci_spec(), false, "mono without self-contact (CI mesh, 3 ms)");
}

TEST(ContactSelfTube, WithoutSelfContactMulti) {
  without_self_contact(ci_spec(), true, "multi without self-contact (CI mesh, 3 ms)");
}

TEST(ContactSelfTube, WithoutSelfContactMonoLong) {
  if (!long_runs()) GTEST_SKIP() << "long crush (minutes): set CRASHLINK_LONG=1";
  without_self_contact(long_spec(), false, "mono without self-contact (fine mesh, 16 ms)");
}

TEST(ContactSelfTube, WithoutSelfContactMultiLong) {
  if (!long_runs()) GTEST_SKIP() << "long crush (minutes): set CRASHLINK_LONG=1";
  without_self_contact(long_spec(), true, "multi without self-contact (fine mesh, 16 ms)");
}
