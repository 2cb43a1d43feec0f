// The `paper` scheme over real processes and sockets (crashlink-coordinator --coupling paper +
// crashlink-solver --coupling paper, or crashlink run --coupling paper) and over inproc threads.
// The coordinator's exchange (coordinator/paper_exchange.h) applies [8]-[11] with the same
// functions in the same order as the in-process cosim::PaperRunner, and the numbers travel as
// packed doubles, so every domain's displacements must be identical to the runner's, bit for bit;
// where the runner's guard stops a run, the coordinator's stops it at the same instant. Every
// suite runs over tcp (ephemeral port read back), ipc and inproc.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/paper_exchange.h"
#include "core/errors.h"
#include "core/exit_codes.h"
#include "inproc_run.h"
#include "paper_reference.h"
#include "process_test_support.h"
#include "solver/cosim/paper_runner.h"
#include "solver/daemon/daemon.h"
#include "solver/io/scenario_reader.h"

using namespace crashlink;
using namespace crashlink::proc_test;
using transport::Scheme;

namespace {

constexpr double kFineStep = 1.0e-6;  // s; the bar's fine part allows ~1.1e-6 s

/// How run_paper runs the coordinator and the daemons.
struct PaperRunOptions {
  bool split = false;                              ///< one common step (else multi)
  bool variable_steps = false;                     ///< CoordinatorOptions::variable_steps
  bool drift = true;                               ///< CoordinatorOptions::drift ([11])
  double step_safety = 1.0;                        ///< every daemon's
  std::map<std::string, double>* steps = nullptr;  ///< inproc: each domain's planned step [s]
  std::map<std::string, std::int64_t>* cycles = nullptr;  ///< inproc: each daemon's cycles
  std::vector<int>* daemon_exit = nullptr;                ///< each daemon's exit code
};

/// Runs the coordinator and one daemon per entry of `cap` (domain -> cap on its proposed step, s;
/// 0: its own). Returns the coordinator's exit code and its message (or output) in `log`.
int run_paper(Scheme scheme, const std::string& scenario, const std::filesystem::path& out,
              const std::map<std::string, double>& cap, std::string& log,
              const PaperRunOptions& ro = {}) {
  if (scheme == Scheme::inproc) {
    coordinator::CoordinatorOptions co;
    co.bind = transport::local_endpoint(Scheme::inproc, "paper");
    co.scenario = scenario;
    co.out_dir = out.string();
    co.run.common_step = ro.split;
    co.run.variable_steps = ro.variable_steps;
    co.run.drift = ro.drift;
    co.run.scheme = "paper";
    const auto r =
        run_inproc(co, cap, [&](daemon::DaemonOptions& d) { d.step_safety = ro.step_safety; });
    log = r.coordinator.message;
    if (ro.steps != nullptr)
      for (const auto& d : r.coordinator.domains)
        (*ro.steps)[d.name] =
            static_cast<double>(d.step_ticks) / static_cast<double>(co.run.ticks_per_second);
    std::size_t k = 0;
    for (const auto& [name, step] : cap) {
      if (ro.cycles != nullptr) (*ro.cycles)[name] = r.daemons[k].cycles;
      if (ro.daemon_exit != nullptr) ro.daemon_exit->push_back(r.daemons[k].exit_code);
      ++k;
    }
    for (const auto& d : r.daemons) log += "\n" + d.message;
    return r.coordinator.exit_code;
  }
  std::string endpoint;
  auto c = start_coordinator(bind_endpoint(scheme, out), scenario, out, "multi", endpoint,
                             {"--coupling", "paper"});
  std::vector<std::unique_ptr<Child>> ds;
  for (const auto& [name, step] : cap)
    ds.push_back(start_solver(endpoint, name, scenario, out,
                              {"--coupling", "paper", "--max-step", fmt::format("{:.17g}", step),
                               "--step-safety", "1"}));  // as inproc (ro.step_safety is 1 here)
  EXPECT_TRUE(ro.steps == nullptr && ro.cycles == nullptr && !ro.split && !ro.variable_steps &&
              ro.step_safety == 1.0)
      << "processes run multi at fixed steps here";
  for (auto& d : ds) {
    const auto st = d->wait(60s);
    EXPECT_TRUE(st.has_value()) << d->output();
    if (ro.daemon_exit != nullptr) ro.daemon_exit->push_back(st ? exit_code(*st) : -999);
  }
  const auto st = c->wait(20s);
  log = c->output();
  for (auto& d : ds) log += "\n" + d->output();
  return st ? exit_code(*st) : -999;
}

std::map<std::string, double> bar_caps(int ratio) {
  return {{"fine", kFineStep}, {"coarse", ratio * kFineStep}};
}

/// A string attribute of an HDF5 object ("" if absent).
std::string string_attribute(const std::string& h5, const std::string& object,
                             const std::string& name) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::string out;
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return out;
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    const hid_t t = H5Aget_type(a);
    if (H5Tis_variable_str(t) > 0) {
      char* s = nullptr;
      if (H5Aread(a, t, &s) >= 0 && s != nullptr) out = s;
      if (s != nullptr) H5free_memory(s);
    } else {
      std::string buf(H5Tget_size(t), '\0');
      if (H5Aread(a, t, buf.data()) >= 0) out = buf.substr(0, buf.find('\0'));
    }
    H5Tclose(t);
    H5Aclose(a);
  }
  H5Fclose(f);
  return out;
}

/// The "at t = ... s" of a guard message.
std::string stop_instant(const std::string& message) {
  const auto a = message.find("went unstable at t = ");
  if (a == std::string::npos) return "(none)";
  const auto b = message.find(' ', a + 21);
  return message.substr(a + 21, b - a - 21);
}

class PaperProcesses : public ::testing::TestWithParam<Scheme> {};

TEST_P(PaperProcesses, ReproduceThePaperRunnerBitForBit) {
  const std::string t(transport::scheme_name(GetParam()));
  const auto dir = fresh_dir("paper-r2-" + t);
  const RemoveIfPassed cleanup{dir};
  // 1e-4 s = 50 coarse steps at r = 2: about one wave transit of the 0.6 m bar, before `paper`'s
  // slow growth at r = 2 (docs/paper-scheme.md) reaches the guard.
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(1.0e-4));
  const auto out = dir / "out";
  std::string log;
  ASSERT_EQ(run_paper(GetParam(), scenario, out, bar_caps(2), log), 0) << log;

  const auto m = io::read_scenario(scenario);
  std::string stopped;
  const auto ref = reference(m, kFineStep, 2 * kFineStep, 50, stopped);
  ASSERT_TRUE(stopped.empty()) << stopped;
  ASSERT_EQ(ref->coarse_steps(), 50);
  expect_runner_bits(out, *ref, "fine", "coarse");
  // The interface history: one row per coarse instant, the gap of the runner's, drift work.
  const std::string h5 = (out / "coordinator.h5").string();
  const auto time = read_doubles(h5, "/coupling/fine-coarse/time");
  const auto gap = read_doubles(h5, "/coupling/fine-coarse/displacement_gap");
  const auto drift = read_doubles(h5, "/coupling/fine-coarse/drift_work");
  ASSERT_EQ(time.size(), 51u);
  ASSERT_EQ(gap.size(), 51u);
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < gap.size(); ++i) worst = std::max(worst, gap[i]);
  EXPECT_NEAR(worst, ref->max_gap().link_m, 1e-12 * ref->max_gap().link_m);
  EXPECT_GT(worst, 0.0);  // the two presences do drift apart between corrections ...
  ASSERT_FALSE(drift.empty());
  EXPECT_NE(drift.back(), 0.0);  // ... and [11] works on them
}

TEST_P(PaperProcesses, UnstableRatioIsStoppedWhereTheRunnerStops) {
  const std::string t(transport::scheme_name(GetParam()));
  const auto dir = fresh_dir("paper-r4-" + t);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(2.0e-4));
  const auto out = dir / "out";
  std::string log;
  std::vector<int> daemon_exit;
  EXPECT_EQ(run_paper(GetParam(), scenario, out, bar_caps(4), log, {.daemon_exit = &daemon_exit}),
            kExitNumerical)
      << log;
  EXPECT_NE(log.find("the coupling went unstable"), std::string::npos) << log;
  ASSERT_EQ(daemon_exit.size(), 2u);
  for (const int c : daemon_exit) EXPECT_EQ(c, kExitPeer) << log;  // stopped by it

  std::string stopped;
  reference(io::read_scenario(scenario), kFineStep, 4 * kFineStep, 50, stopped);
  ASSERT_FALSE(stopped.empty()) << "the runner was expected to stop at r = 4";
  EXPECT_EQ(stop_instant(log), stop_instant(stopped)) << log << "\n" << stopped;
  // What was written stays readable and finite.
  for (const std::string name : {"fine", "coarse"}) {
    const auto s = last_state((out / "domains" / (name + ".h5")).string());
    ASSERT_TRUE(s.ok()) << name;
    for (const double x : s.u) ASSERT_TRUE(std::isfinite(x)) << name;
  }
}

// Drift correction [11] off (the study's S2, --no-drift): still the runner's run, bit for bit,
// and the presences drift further apart than with [11].
TEST(PaperProcessesNoDrift, ReproducesTheRunnerWithoutDriftCorrection) {
  const auto dir = fresh_dir("paper-nodrift");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(1.0e-4));
  const auto out = dir / "out";
  std::string log;
  ASSERT_EQ(run_paper(Scheme::inproc, scenario, out, bar_caps(2), log, {.drift = false}), 0) << log;
  const auto m = io::read_scenario(scenario);
  std::string stopped;
  const auto off = reference(m, kFineStep, 2 * kFineStep, 50, stopped, false);
  ASSERT_TRUE(stopped.empty()) << stopped;
  const auto on = reference(m, kFineStep, 2 * kFineStep, 50, stopped, true);
  expect_runner_bits(out, *off, "fine", "coarse");
  const std::string h5 = (out / "coordinator.h5").string();
  const auto drift = read_doubles(h5, "/coupling/fine-coarse/drift_work");
  ASSERT_FALSE(drift.empty());
  EXPECT_EQ(drift.back(), 0.0);  // no [11], no drift work
  EXPECT_GT(off->max_gap().link_m, on->max_gap().link_m);
}

// A daemon started for the other scheme is refused at its Register, both ways round, with the
// fix (the same --coupling everywhere); the coordinator exits 2 (input), the daemon non-zero.
// Processes only (the flags are the command lines').
TEST(PaperProcessesCli, MismatchedCouplingIsRefusedWithTheFix) {
  for (const auto& [scheme, coordinator_paper] : {std::pair{Scheme::tcp, true},
                                                  {Scheme::tcp, false},
                                                  {Scheme::ipc, true},
                                                  {Scheme::ipc, false}}) {
    const std::string t(transport::scheme_name(scheme));
    const auto dir = fresh_dir(std::string("paper-mix-") + t + (coordinator_paper ? "-c" : "-d"));
    const RemoveIfPassed cleanup{dir};
    const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(1.0e-4));
    const auto out = dir / "out";
    const std::vector<std::string> paper{"--coupling", "paper"};
    std::string endpoint;
    auto c = start_coordinator(bind_endpoint(scheme, out), scenario, out, "multi", endpoint,
                               coordinator_paper ? paper : std::vector<std::string>{});
    auto d = start_solver(endpoint, "fine", scenario, out,
                          coordinator_paper ? std::vector<std::string>{} : paper);
    const auto cs = c->wait(20s);
    const auto ds = d->wait(20s);
    ASSERT_TRUE(cs.has_value()) << c->output();
    ASSERT_TRUE(ds.has_value()) << d->output();
    EXPECT_EQ(exit_code(*cs), kExitInput) << c->output();
    EXPECT_NE(exit_code(*ds), 0) << d->output();
    EXPECT_NE(c->output().find("--coupling"), std::string::npos) << c->output();
    EXPECT_NE(c->output().find("'fine'"), std::string::npos) << c->output();
  }
}

INSTANTIATE_TEST_SUITE_P(Transports, PaperProcesses,
                         ::testing::Values(Scheme::tcp, Scheme::ipc, Scheme::inproc),
                         scheme_test_name);

/// Contact across domains (§3.1 of Bourel 2005): scenarios/plate_impact_small.yaml cut into the
/// rigid headform and the plate, 1 ms (the impact starts at 0.2 ms). The headform's domain holds
/// copies of the plate's 441 nodes and computes the contact on them; over threads the run must be
/// PaperRunner's, bit for bit, at the steps the coordinator planned.
TEST(PaperProcessesContact, CopiesReproduceThePaperRunnerBitForBit) {
  const auto dir = fresh_dir("paper-contact");
  const RemoveIfPassed cleanup{dir};
  std::ifstream in(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/plate_impact_small.yaml");
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = yaml.find("end_time: 0.008");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, 15, "end_time: 0.001");
  yaml += "domains:\n  head: {parts: [headform]}\n  plate: {parts: [plate]}\n";
  const std::string scenario = write_file(dir / "pis.yaml", yaml);
  const auto out = dir / "out";
  std::string log;
  std::map<std::string, double> steps;
  ASSERT_EQ(run_paper(Scheme::inproc, scenario, out, {{"head", 0.0}, {"plate", 0.0}}, log,
                      {.steps = &steps}),
            0)
      << log;
  ASSERT_GT(steps["plate"], 0.0);
  ASSERT_GE(steps["head"], steps["plate"]);
  const auto m = io::read_scenario(scenario);
  std::string stopped;
  const auto coarse = static_cast<std::int64_t>(std::ceil(1.0e-3 / steps["head"] - 1e-9));
  const auto ref = reference(m, steps["plate"], steps["head"], coarse, stopped);
  ASSERT_TRUE(stopped.empty()) << stopped;
  EXPECT_EQ(ref->coupled_nodes().size(), 441u);
  expect_runner_bits(out, *ref, "plate", "head");
  // The copies touched: the plate moved under the headform.
  EXPECT_GT(ref->max_gap().copy_m, 0.0);
}

/// A steel bar of hexes in three parts and domains: fine [0, 0.2] m (10 mm), mid [0.2, 0.4] m
/// (20 mm), coarse [0.4, 0.6] m (40 mm); far end fixed, a force pulse on x = 0.
std::string bar3_yaml(double end_time_s) {
  return bar_parts_yaml("bar3", end_time_s,
                        {{"fine", 0.0, 0.2, 20}, {"mid", 0.2, 0.2, 10}, {"coarse", 0.4, 0.2, 5}});
}

/// The three-domain bar run by threads at one common step (fixed, or each instant the smallest
/// proposal), and mono stepped the same way: max |u - u_mono| / max |u| over the three domains.
double three_domain_split_vs_mono(bool variable, const std::string& label) {
  const auto dir = fresh_dir(label);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar3.yaml", bar3_yaml(2.0e-4));
  const auto out = dir / "out";
  std::string log;
  std::map<std::string, double> steps;
  std::map<std::string, std::int64_t> cycles;
  // Fixed steps need a margin: the fine part's stable step shrinks under the pulse.
  const double safety = variable ? 1.0 : 0.9;
  const int rc =
      run_paper(Scheme::inproc, scenario, out, {{"fine", 0.0}, {"mid", 0.0}, {"coarse", 0.0}}, log,
                {.split = true,
                 .variable_steps = variable,
                 .step_safety = safety,
                 .steps = &steps,
                 .cycles = &cycles});
  EXPECT_EQ(rc, 0) << log;
  if (rc != 0) return 1.0;
  const auto tps = coupling::kDefaultTicksPerSecond;
  const auto h = static_cast<coupling::Tick>(std::llround(steps["fine"] * tps));
  for (const auto& [name, step] : steps) EXPECT_EQ(step, steps["fine"]) << name;

  // Mono: fixed, the common step to the coordinator's end; variable, the daemons' rule at every
  // cycle (floor(dt x ticks) of its own stable step) held as the coordinator holds the common
  // step (coupling::Schedule, integration::held_step), until the first instant >= the end time.
  const auto m = io::read_scenario(scenario);
  integration::Solver mono(m, "mono");
  mono.initialize();
  double in_force = 0.0;  // ticks
  const auto own = [&] {
    in_force = integration::held_step(std::floor(mono.dt_s() * static_cast<double>(tps)), in_force);
    return in_force / static_cast<double>(tps);
  };
  const auto end = coordinator::paper_end_ticks(2.0e-4, {h}, tps);
  std::int64_t n = 0;
  for (;; ++n) {
    mono.impose_step(variable ? own() : static_cast<double>(h) / static_cast<double>(tps));
    mono.begin_cycle();
    if (variable ? mono.finished() : n == end / h) break;
    mono.end_cycle();
  }
  double worst = 0.0, scale = 0.0;
  for (const std::string name : {"fine", "mid", "coarse"}) {
    const auto s = last_state((out / "domains" / (name + ".h5")).string());
    EXPECT_TRUE(s.ok()) << name;
    if (!s.ok()) return 1.0;
    EXPECT_NEAR(s.time_s, mono.time_s(), 1e-12) << name;
    const double d = max_difference(s, mono);
    EXPECT_GE(d, 0.0) << name;
    worst = std::max(worst, d);
  }
  for (const double u : mono.displacement()) scale = std::max(scale, std::abs(u));
  for (const auto& [name, c] : cycles) EXPECT_EQ(c, n) << name << ": the steps imposed differ";
  EXPECT_GT(scale, 0.0);
  std::printf(
      "[measured] paper split, three domains, %s steps, %lld cycles to t = %.4e s: max "
      "|u - u_mono| / max |u| = %.2e\n",
      variable ? "variable" : "fixed", static_cast<long long>(n), mono.time_s(), worst / scale);
  if (!variable) {  // the two interfaces each have their history, marked `paper`
    const std::string h5 = (out / "coordinator.h5").string();
    EXPECT_EQ(read_doubles(h5, "/coupling/fine-mid/time").size(), static_cast<std::size_t>(n) + 1);
    EXPECT_EQ(read_doubles(h5, "/coupling/mid-coarse/time").size(),
              static_cast<std::size_t>(n) + 1);
  }
  return scale > 0.0 ? worst / scale : 1.0;
}

/// Three domains (two interfaces, the middle domain in both): split at one common step sums the
/// free accelerations of [8] into the single-domain acceleration, so it reproduces mono at that
/// step to round-off (docs/design.md §4: <= 1e-10 relative).
TEST(PaperProcessesThreeDomains, SplitReproducesMono) {
  EXPECT_LE(three_domain_split_vs_mono(false, "paper-3"), 1e-10);
}

/// The same with variable steps (docs/design.md §2.6: the smallest proposal of all at every
/// instant, the run ending at the first instant at or after the end time): mono stepping by the
/// same rule.
TEST(PaperProcessesThreeDomains, VariableSplitReproducesMonoAtItsOwnSteps) {
  EXPECT_LE(three_domain_split_vs_mono(true, "paper-3v"), 1e-10);
}

/// `crashlink run --coupling paper`: split at r = 1 closes the energy balance (the daemons'
/// accounts, gathered), and the run's history is marked `paper`.
TEST(PaperRun, SplitRunClosesTheEnergyBalance) {
  const auto dir = fresh_dir("paper-run");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar2.yaml", bar_yaml(1.0e-4));
  const auto out = dir / "out";
  std::vector<std::string> argv{bin("crashlink"), "run",   scenario, "--mode",     "split",
                                "--coupling",     "paper", "--out",  out.string(), "--quiet"};
  for (const auto& s : fast_session_args()) argv.push_back(s);
  Child run(argv);
  const auto st = run.wait(90s);
  ASSERT_TRUE(st.has_value()) << run.output();
  ASSERT_EQ(exit_code(*st), 0) << run.output();
  const auto err =
      read_doubles((out / "result.h5").string(), "/history/glstat/energy_balance_error");
  ASSERT_FALSE(err.empty());
  double worst = 0.0;
  for (const double e : err) worst = std::max(worst, std::abs(e));
  // Each domain's balance closes to round-off at a constant step (the link and drift work are
  // counted with the Solver's trapezoid rule); 1e-5 leaves room for the summing.
  EXPECT_LT(worst, 1e-5) << run.output();
  // The interface history is marked `paper` (the attribute io::CouplingHistoryWriter writes).
  const std::string h5 = (out / "coordinator.h5").string();
  EXPECT_EQ(string_attribute(h5, "/coupling/fine-coarse", "scheme"), "paper");
  EXPECT_EQ(read_doubles(h5, "/coupling/fine-coarse/time").size(),
            read_doubles(h5, "/coupling/fine-coarse/velocity_jump").size());
}

/// Variable steps in multi (each domain its own proposal: the three-domain bar runs at ratios
/// of about 1.9 and 1.7, not whole): `paper` goes unstable and its guard, sampling the domains'
/// latest energies, stops the run with its message; the daemons are stopped by it.
TEST(PaperProcessesThreeDomains, VariableMultiIsStoppedByTheGuard) {
  const auto dir = fresh_dir("paper-3vm");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar3.yaml", bar3_yaml(4.0e-4));
  std::string log;
  std::vector<int> daemon_exit;
  EXPECT_EQ(run_paper(Scheme::inproc, scenario, dir / "out",
                      {{"fine", 0.0}, {"mid", 0.0}, {"coarse", 0.0}}, log,
                      {.variable_steps = true, .daemon_exit = &daemon_exit}),
            kExitNumerical)
      << log;
  EXPECT_NE(log.find("the coupling went unstable"), std::string::npos) << log;
  EXPECT_NE(log.find("variable steps, initially"), std::string::npos) << log;
  for (const int c : daemon_exit) EXPECT_NE(c, 0) << log;
}

}  // namespace
