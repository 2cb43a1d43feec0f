// The `layer` scheme over real processes and sockets (crashlink run --mode split|multi, or
// crashlink-coordinator + crashlink-solver started by hand) and over inproc threads: the daemons
// run the same LayerStepper as the in-process cosim::LayerNetwork, only the messages travel over
// ZeroMQ (packed doubles, bit for bit), so the nodal displacements must be identical to it; split
// must also reproduce mono at the same step to round-off (docs/design.md §4: <= 1e-10 relative).
// Every suite runs over tcp (ephemeral port read back), ipc and inproc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "process_test_support.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_network.h"
#include "solver/cosim/layer_stepper.h"
#include "solver/daemon/daemon.h"
#include "solver/integration/solver.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"

using namespace crashlink;
using namespace crashlink::proc_test;
using transport::Scheme;

namespace {

/// max |u - ref| over the nodes of a result file, ref indexed by global node (model order).
struct Diff {
  double max_abs = -1.0;  ///< -1: nothing compared
  double scale = 0.0;     ///< max |ref| over the same nodes
  std::size_t nodes = 0;
  double rel() const { return scale > 0.0 ? max_abs / scale : max_abs; }
};

Diff compare(const LastState& s, const model::Model& m, const std::vector<double>& ref) {
  Diff d;
  if (!s.ok()) return d;
  std::map<std::int64_t, std::size_t> index;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) index[m.nodes.id[i]] = i;
  d.max_abs = 0.0;
  for (std::size_t i = 0; i < s.node_ids.size(); ++i) {
    const auto it = index.find(s.node_ids[i]);
    if (it == index.end()) return Diff{};
    for (std::size_t c = 0; c < 3; ++c) {
      const double r = ref[3 * it->second + c];
      d.scale = std::max(d.scale, std::abs(r));
      d.max_abs = std::max(d.max_abs, std::abs(s.u[3 * i + c] - r));
    }
    ++d.nodes;
  }
  return d;
}

/// The reference: every domain's stepper in this thread.
struct Reference {
  std::vector<double> u;                ///< [3 n_global] at the end
  std::vector<double> mono_u;           ///< mono at the common step (split only)
  std::vector<coupling::Tick> steps;    ///< [domains] the plan
  std::int64_t cycles = 0;              ///< cycles of the first domain
  std::vector<std::int64_t> cycles_of;  ///< [domains]
  std::vector<double> coupling_work_J;  ///< [domains] each solver's coupling work at the end
};

Reference reference(const model::Model& m, const cosim::LayerNetworkOptions& o) {
  Reference r;
  cosim::LayerNetwork net(m, o);
  net.initialize();
  EXPECT_TRUE(net.run());
  r.u = net.global_displacement();
  r.steps = net.plan().step;
  r.cycles = net.solver(0).cycle();
  for (std::size_t k = 0; k < net.size(); ++k) {
    r.coupling_work_J.push_back(net.solver(k).energy().coupling_work_J);
    r.cycles_of.push_back(net.solver(k).cycle());
  }
  if (o.run.common_step && !o.run.variable_steps) {
    integration::Solver mono(m, "mono");
    const double h = net.seconds(net.plan().step[0]);
    mono.initialize();
    mono.impose_step(h);
    for (std::int64_t n = 0; n < r.cycles; ++n) {
      mono.begin_cycle();
      mono.end_cycle();
      mono.impose_step(h);
    }
    r.mono_u = mono.displacement();
  }
  return r;
}

/// Runs the coordinator and one daemon per domain, as processes (tcp, ipc) or threads (inproc);
/// daemon_extra[d] are extra crashlink-solver arguments. Returns the coordinator's exit code.
int run_pieces(Scheme scheme, const std::string& scenario, const std::filesystem::path& out,
               const std::string& mode,
               const std::vector<std::pair<std::string, std::vector<std::string>>>& daemons,
               std::string& log, bool lanes = true, bool variable = false) {
  if (scheme == Scheme::inproc) {
    coordinator::CoordinatorOptions co;
    co.bind = transport::local_endpoint(Scheme::inproc, "test");
    co.scenario = scenario;
    co.out_dir = out.string();
    co.run.common_step = mode == "split";
    co.in_process = true;
    co.log = nullptr;
    co.run.lanes = lanes;
    co.run.variable_steps = variable;
    coordinator::CoordinatorResult cr;
    std::thread c([&] { cr = coordinator::run_coordinator(co); });
    std::vector<daemon::DaemonResult> dr(daemons.size());
    std::vector<std::thread> ds;
    for (std::size_t k = 0; k < daemons.size(); ++k) {
      ds.emplace_back([&, k] {
        daemon::DaemonOptions d;
        d.endpoint = co.bind;  // inproc: connecting before the bind is fine
        d.domain = daemons[k].first;
        d.scenario = scenario;
        d.out_dir = out.string();
        d.in_process = true;
        const auto& x = daemons[k].second;
        for (std::size_t i = 0; i + 1 < x.size(); i += 2) {
          if (x[i] == "--max-step") d.max_step_s = std::stod(x[i + 1]);
          if (x[i] == "--step-safety") d.step_safety = std::stod(x[i + 1]);
        }
        dr[k] = daemon::run_daemon(d);
      });
    }
    for (auto& t : ds) t.join();
    c.join();
    log = cr.message + (cr.lanes ? "layer vectors daemon to daemon (lanes)"
                                 : "layer vectors through the coordinator");
    for (const auto& d : dr) {
      log += d.message;
      EXPECT_EQ(d.exit_code, 0) << d.message;
    }
    return cr.exit_code;
  }
  std::string endpoint;
  std::vector<std::string> coordinator_args;
  if (!lanes) coordinator_args.emplace_back("--no-lanes");
  if (variable) coordinator_args.emplace_back("--variable-steps");
  auto c = start_coordinator(bind_endpoint(scheme, out), scenario, out, mode, endpoint,
                             coordinator_args);
  std::vector<std::unique_ptr<Child>> ds;
  for (const auto& [name, extra] : daemons) {
    ds.push_back(start_solver(endpoint, name, scenario, out, extra));
  }
  for (auto& d : ds) {
    const auto st = d->wait(60s);
    EXPECT_TRUE(st && exit_code(*st) == 0) << d->output();
  }
  const auto st = c->wait(20s);
  log = c->output();
  return st ? exit_code(*st) : -999;
}

/// The coordinator's interface history (DIR/coordinator.h5): one row per owner instant, and its
/// link work is the work of the layer's force and moment on J, which the owner counts as its
/// coupling work. Returns {link work, owner's coupling work} at the end.
std::pair<double, double> interface_history(const std::filesystem::path& out, const model::Model& m,
                                            const Reference& ref) {
  const auto dec = partition::decompose(m, partition::Scheme::Layer);
  EXPECT_EQ(dec.interfaces.size(), 1u);
  if (dec.interfaces.size() != 1) return {0.0, 0.0};
  const auto& itf = dec.interfaces[0];
  const auto coarse = static_cast<std::size_t>(itf.coarse);
  const std::string iface = "/coupling/" + dec.domains[static_cast<std::size_t>(itf.fine)].name +
                            "-" + dec.domains[coarse].name;
  const auto time = read_doubles((out / "coordinator.h5").string(), iface + "/time");
  const auto work = read_doubles((out / "coordinator.h5").string(), iface + "/link_work");
  EXPECT_EQ(time.size(), static_cast<std::size_t>(ref.cycles_of[coarse]) + 1) << iface;
  EXPECT_EQ(work.size(), time.size()) << iface;
  if (work.empty()) return {0.0, ref.coupling_work_J[coarse]};
  const double owner = ref.coupling_work_J[coarse];
  EXPECT_NEAR(work.back(), owner, 1e-9 * std::abs(owner) + 1e-15) << iface;
  return {work.back(), owner};
}

/// Each domain file's last state against LayerNetwork's displacements: read, moved, and equal to
/// the bit. Returns the largest relative difference and each domain's last time [s] (-1 for a
/// file that could not be read).
struct NetworkMatch {
  double worst = 0.0;
  std::vector<double> end_times;
};
NetworkMatch expect_network_bits(const std::filesystem::path& out, const model::Model& m,
                                 const Reference& ref, const std::vector<std::string>& domains) {
  NetworkMatch r;
  for (const auto& d : domains) {
    const auto s = last_state((out / "domains" / (d + ".h5")).string());
    EXPECT_TRUE(s.ok()) << d;
    r.end_times.push_back(s.time_s);
    const Diff net = compare(s, m, ref.u);
    EXPECT_GE(net.max_abs, 0.0) << d;
    EXPECT_GT(net.scale, 0.0) << d;
    EXPECT_EQ(net.max_abs, 0.0) << d << ": not bit-identical to LayerNetwork";
    r.worst = std::max(r.worst, net.rel());
  }
  return r;
}

class LayerProcesses : public ::testing::TestWithParam<Scheme> {
 protected:
  std::string scheme() const { return std::string(transport::scheme_name(GetParam())); }
};

/// `crashlink run --mode split --transport T` on `scenario`; compares every domain file, the
/// gathered result.h5 and mono with the reference.
void split_case(Scheme scheme, const std::string& label, const std::string& yaml,
                const std::vector<std::string>& domains) {
  const std::string t(transport::scheme_name(scheme));
  const auto dir = fresh_dir("split-" + label + "-" + t);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / (label + ".yaml"), yaml);
  const auto out = dir / "out";
  std::vector<std::string> argv{bin("crashlink"), "run", scenario, "--mode",     "split",
                                "--transport",    t,     "--out",  out.string(), "--quiet",
                                "--step-safety",  "0.9"};
  for (const auto& s : fast_session_args()) argv.push_back(s);
  const auto t0 = Clock::now();
  Child run(argv);
  const auto st = run.wait(90s);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  ASSERT_TRUE(st.has_value()) << "crashlink run did not end within 90 s\n" << run.output();
  ASSERT_EQ(exit_code(*st), 0) << run.output();
  EXPECT_NE(run.output().find("coordinator: CPU"), std::string::npos) << run.output();

  const auto m = io::read_scenario(scenario);
  cosim::LayerNetworkOptions o;
  o.run.common_step = true;
  o.step_safety = 0.9;
  const Reference ref = reference(m, o);
  double worst_net = 0.0, worst_mono = 0.0;
  for (const auto& d : domains) {
    const auto s = last_state((out / "domains" / (d + ".h5")).string());
    ASSERT_TRUE(s.ok()) << d;
    const Diff net = compare(s, m, ref.u);
    const Diff mono = compare(s, m, ref.mono_u);
    ASSERT_GE(net.max_abs, 0.0) << d;
    EXPECT_GT(net.scale, 0.0) << d;
    EXPECT_EQ(net.max_abs, 0.0) << d << ": not bit-identical to LayerNetwork";
    EXPECT_LE(mono.rel(), 1e-10) << d;
    worst_net = std::max(worst_net, net.rel());
    worst_mono = std::max(worst_mono, mono.rel());
  }
  const auto [link_work, owner_work] = interface_history(out, m, ref);
  const auto g = last_state((out / "result.h5").string());
  const Diff gathered = compare(g, m, ref.u);
  EXPECT_EQ(gathered.max_abs, 0.0) << "gathered result.h5";
  std::printf(
      "[measured] split over %s, %s: %lld cycles of %.4e s, %zu domains, wall %.2f s; max "
      "|u - u_network| / max|u| = %.3e (domain files), %.3e (gathered result.h5, %zu nodes); "
      "vs mono at the same step: %.3e; link work %.6e J (owner's coupling work %.6e J)\n",
      t.c_str(), label.c_str(), static_cast<long long>(ref.cycles),
      static_cast<double>(ref.steps[0]) * 1e-15, domains.size(), wall, worst_net, gathered.rel(),
      gathered.nodes, worst_mono, link_work, owner_work);
}

}  // namespace

TEST_P(LayerProcesses, SplitBarReproducesNetworkAndMono) {
  split_case(GetParam(), "bar", bar_yaml(1.2e-2), {"fine", "coarse"});
}

TEST_P(LayerProcesses, SplitShellPlateReproducesNetworkAndMono) {
  split_case(GetParam(), "plate", plate_yaml(4.0e-3), {"left", "right"});
}

// multi at ratio 2: the fine domain proposes 1 us, the coarse 2 us (--max-step, as
// LayerNetworkOptions::proposal_s), so the plan is H = 2 h. The layer vectors go daemon to daemon
// (lanes, docs/processes.md) or, with --no-lanes, through the coordinator: the same bits either
// way, and the interface history the fine side reports is the owner's coupling work.
static void multi_bar_case(Scheme scheme, bool lanes) {
  const std::string t(transport::scheme_name(scheme));
  const auto dir = fresh_dir(std::string("multi-bar-") + (lanes ? "lanes-" : "routed-") + t);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(6.0e-3));
  const auto out = dir / "out";
  std::string log;
  // --step-safety 1: LayerNetworkOptions' (crashlink-solver's default is 0.9, as crashlink run's)
  const int code = run_pieces(scheme, scenario, out, "multi",
                              {{"fine", {"--max-step", "1e-6", "--step-safety", "1"}},
                               {"coarse", {"--max-step", "2e-6", "--step-safety", "1"}}},
                              log, lanes);
  ASSERT_EQ(code, 0) << log;
  EXPECT_NE(log.find(lanes ? "layer vectors daemon to daemon (lanes)"
                           : "layer vectors through the coordinator"),
            std::string::npos)
      << log;

  const auto m = io::read_scenario(scenario);
  cosim::LayerNetworkOptions o;
  o.run.common_step = false;
  o.proposal_s = {1e-6, 2e-6};  // solver order = domain order: fine, coarse
  const Reference ref = reference(m, o);
  ASSERT_EQ(ref.steps.size(), 2u);
  EXPECT_EQ(ref.steps[1], 2 * ref.steps[0]) << "the plan is not at ratio 2";
  const double worst = expect_network_bits(out, m, ref, {"fine", "coarse"}).worst;
  const auto [link_work, owner_work] = interface_history(out, m, ref);
  std::printf(
      "[measured] multi over %s (%s), bar at H/h = %lld/%lld ticks: max |u - u_network| / "
      "max|u| = %.3e; link work %.6e J (owner's coupling work %.6e J)\n",
      t.c_str(), lanes ? "lanes" : "through the coordinator", static_cast<long long>(ref.steps[1]),
      static_cast<long long>(ref.steps[0]), worst, link_work, owner_work);
}

TEST_P(LayerProcesses, MultiBarAtRatio2IsNetworkToTheBit) {
  multi_bar_case(GetParam(), true);
}

TEST_P(LayerProcesses, MultiBarThroughTheCoordinatorIsNetworkToTheBit) {
  multi_bar_case(GetParam(), false);
}

// Variable steps (--variable-steps; cosim::LayerSteps::Variable): the bar's meshes make the
// ratio (1 cm fine, 2 cm coarse elements), the coarse daemon chooses every step from its own
// proposal and the fine one's, which rides on g_A, and the fine daemon commits its substeps from
// the time of u_J: the same choices and the same bits as LayerNetwork, with lanes and through the
// coordinator (whose router then only checks the time order).
static void multi_bar_variable_case(Scheme scheme, bool lanes) {
  const std::string t(transport::scheme_name(scheme));
  const auto dir = fresh_dir(std::string("variable-bar-") + (lanes ? "lanes-" : "routed-") + t);
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(dir / "bar.yaml", bar_yaml(6.0e-3));
  const auto out = dir / "out";
  std::string log;
  // --step-safety 1: LayerNetworkOptions' (crashlink-solver's default is 0.9, as crashlink run's)
  const std::vector<std::string> safety{"--step-safety", "1"};
  const int code = run_pieces(scheme, scenario, out, "multi",
                              {{"fine", safety}, {"coarse", safety}}, log, lanes, true);
  ASSERT_EQ(code, 0) << log;
  const auto m = io::read_scenario(scenario);
  cosim::LayerNetworkOptions o;
  o.run.variable_steps = true;
  const Reference ref = reference(m, o);
  expect_network_bits(out, m, ref, {"fine", "coarse"});
  const auto [link_work, owner_work] = interface_history(out, m, ref);
  std::printf(
      "[measured] multi over %s (%s), bar, variable steps: %lld fine and %lld coarse cycles, "
      "bit-identical to LayerNetwork; link work %.6e J (owner's coupling work %.6e J)\n",
      t.c_str(), lanes ? "lanes" : "through the coordinator",
      static_cast<long long>(ref.cycles_of[0]), static_cast<long long>(ref.cycles_of[1]), link_work,
      owner_work);
}

TEST_P(LayerProcesses, MultiBarVariableStepsIsNetworkToTheBit) {
  multi_bar_variable_case(GetParam(), true);
}

TEST_P(LayerProcesses, MultiBarVariableStepsThroughTheCoordinatorIsNetworkToTheBit) {
  multi_bar_variable_case(GetParam(), false);
}

// Three domains in a chain, fine | mid | coarse (5, 10 and 30 mm hexes), ended at a time that is
// no instant of the coarse domain. Every domain must end together: with fixed steps at the first
// common instant after the end time (coupling::aligned_end, sent with the Setup), with variable
// steps when the leader's u_J says it is its last. Before session 10's fix the fine domain stopped
// at mid's first instant after the end time and mid waited for it forever (seen in process). The
// daemons must give LayerNetwork's bits, every domain's last state at the same time.
static void chain_case(Scheme scheme, bool variable, bool split = false) {
  const std::string t(transport::scheme_name(scheme));
  const auto dir = fresh_dir(std::string("chain3-") + (split ? "split-" : "") +
                             (variable ? "variable-" : "fixed-") + t);
  const RemoveIfPassed cleanup{dir};
  const double end_s = 2.11e-4;
  const std::string scenario = write_file(
      dir / "chain.yaml",
      bar_parts_yaml("chain3", end_s,
                     {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}}));
  const auto out = dir / "out";
  std::string log;
  // Fixed steps at 0.8 of the initial stable steps: at 0.9 the coarse bar's stable step falls
  // below its fixed step under the pulse, and the run stops with impose_step's error.
  const std::vector<std::string> safety{"--step-safety", "0.8"};
  const int code =
      run_pieces(scheme, scenario, out, split ? "split" : "multi",
                 {{"fine", safety}, {"mid", safety}, {"coarse", safety}}, log, true, variable);
  ASSERT_EQ(code, 0) << log;
  const auto m = io::read_scenario(scenario);
  cosim::LayerNetworkOptions o;
  o.run.variable_steps = variable;
  o.run.common_step = split;
  o.step_safety = 0.8;
  const Reference ref = reference(m, o);
  ASSERT_EQ(ref.cycles_of.size(), 3u);
  const std::vector<double> end_times =
      expect_network_bits(out, m, ref, {"fine", "mid", "coarse"}).end_times;
  // Each domain's time is its own sum of steps in seconds: equal up to that sum's round-off.
  EXPECT_NEAR(end_times[0], end_times[1], 1e-12 * end_times[1]);
  EXPECT_NEAR(end_times[1], end_times[2], 1e-12 * end_times[1]);
  if (!variable) {
    // In ticks, exactly: cycles x step is the same instant for the three domains.
    ASSERT_EQ(ref.steps.size(), 3u);
    EXPECT_EQ(ref.cycles_of[0] * ref.steps[0], ref.cycles_of[1] * ref.steps[1]);
    EXPECT_EQ(ref.cycles_of[1] * ref.steps[1], ref.cycles_of[2] * ref.steps[2]);
    EXPECT_GT(end_times[2], end_s) << "the end time is a coarse instant: no test";
  }
  std::printf(
      "[measured] chain of three over %s, %s%s steps: %lld / %lld / %lld cycles, all ending at "
      "%.6e s (end time %.6e s), bit-identical to LayerNetwork\n",
      t.c_str(), split ? "split, " : "", variable ? "variable" : "fixed",
      static_cast<long long>(ref.cycles_of[0]), static_cast<long long>(ref.cycles_of[1]),
      static_cast<long long>(ref.cycles_of[2]), end_times[0], end_s);
}

TEST_P(LayerProcesses, ThreeDomainChainEndsTogetherAndIsNetworkToTheBit) {
  chain_case(GetParam(), false);
}

TEST_P(LayerProcesses, ThreeDomainChainWithVariableStepsIsNetworkToTheBit) {
  chain_case(GetParam(), true);
}

// Split with variable steps: every domain at the least proposal of all, which reaches the leader
// (coarse) only through mid's g_A (LayerSteps::VariableCommon): one cycle count for all.
TEST_P(LayerProcesses, ThreeDomainChainSplitWithVariableStepsIsNetworkToTheBit) {
  chain_case(GetParam(), true, true);
}

INSTANTIATE_TEST_SUITE_P(Transports, LayerProcesses,
                         ::testing::Values(Scheme::tcp, Scheme::ipc, Scheme::inproc),
                         scheme_test_name);

// Overlap (docs/design.md §2.6): LayerStepper::set_on_outbox offers u_J(t + h) while the stepper is
// still at t at the latest (predicted right after g_A(t) is applied; after the positions at t + h
// at the first step), before the forces there (the stepper moves to t + h only after
// Solver::end_cycle_compute), and g_A(t + h) right after those forces. A daemon
// sends from that callback, so the partner works while this domain computes its forces. Messages
// delivered straight from the callbacks (the earliest possible moment) give LayerNetwork's run to
// the bit, at ratio 2.
TEST(LayerStepperOverlap, DisplacementLeavesBeforeTheForcesAndTheRunIsUnchanged) {
  const auto m = io::parse_scenario(bar_yaml(1.0e-3), "bar.yaml");
  cosim::LayerNetworkOptions o;
  o.run.common_step = false;
  o.proposal_s = {1e-6, 2e-6};
  const Reference ref = reference(m, o);
  ASSERT_EQ(ref.steps.size(), 2u);
  ASSERT_EQ(ref.steps[1], 2 * ref.steps[0]);

  auto d = cosim::build_layer_domains(m, "overlap test");
  ASSERT_EQ(d.solvers.size(), 2u);
  std::vector<std::size_t> solver_of(d.dec.domains.size(), cosim::kNoSolver);
  for (std::size_t k = 0; k < d.domain_of.size(); ++k)
    solver_of[static_cast<std::size_t>(d.domain_of[k])] = k;
  auto ports = cosim::layer_ports(d);
  std::vector<std::unique_ptr<cosim::LayerStepper>> st;
  for (std::size_t k = 0; k < 2; ++k) {
    d.solvers[k]->initialize();
    for (auto& p : ports[k]) {
      const auto coarse = solver_of[static_cast<std::size_t>(d.dec.interfaces[p.index].coarse)];
      if (p.fine_side) p.partner_step = ref.steps[coarse];
    }
    st.push_back(std::make_unique<cosim::LayerStepper>(*d.solvers[k], std::move(ports[k]),
                                                       ref.steps[k], o.run.ticks_per_second));
  }
  std::int64_t early_displacements = 0, early_forces = 0, offers = 0;
  auto route = [&](std::size_t from) {
    for (auto& msg : st[from]->take_outbox()) st[1 - from]->deliver(msg);
  };
  for (std::size_t k = 0; k < 2; ++k) {
    st[k]->set_on_outbox([&, k] {
      ++offers;
      const auto& s = *st[k];
      for (const auto& msg : s.outbox()) {
        if (msg.kind == cosim::LayerMessage::Kind::Displacement) {
          EXPECT_EQ(msg.time, s.time() + s.step()) << "u_J(t + h) must leave before t + h";
          early_displacements += msg.time == s.time() + s.step();
        } else {
          EXPECT_EQ(msg.time, s.time()) << "g_A(t) must leave as soon as it is computed";
          early_forces += msg.time == s.time();
        }
      }
      route(k);
    });
    st[k]->initialize();
  }
  for (std::size_t k = 0; k < 2; ++k) route(k);  // g_A(0)
  using Wait = cosim::LayerStepper::Wait;
  for (int guard = 0; guard < 1000000; ++guard) {
    const Wait a = st[0]->advance();
    const Wait b = st[1]->advance();
    EXPECT_FALSE(st[0]->has_outbox() || st[1]->has_outbox()) << "a message stayed in an outbox";
    if (a == Wait::Finished && b == Wait::Finished) break;
  }
  ASSERT_EQ(st[0]->waiting(), Wait::Finished);
  ASSERT_EQ(st[1]->waiting(), Wait::Finished);
  EXPECT_GT(early_displacements, 0);
  EXPECT_GT(early_forces, 0);
  const auto u = cosim::global_displacement(d);
  ASSERT_EQ(u.size(), ref.u.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) worst = std::max(worst, std::abs(u[i] - ref.u[i]));
  EXPECT_EQ(worst, 0.0) << "sending from set_on_outbox changed the run";
  std::printf(
      "[measured] overlap: %lld offers (%lld u_J before the forces, %lld g_A), max |u - "
      "u_network| = %.3e\n",
      static_cast<long long>(offers), static_cast<long long>(early_displacements),
      static_cast<long long>(early_forces), worst);
}

/// `crashlink run SCENARIO --mode multi --coupling lts --transport TRANSPORT --step-safety SAFETY
/// --out OUT --quiet` (and the fast session options) to its end within 90 s; fails the test on a
/// time-out or a non-zero exit. The lts network options of the same run (for reference()).
static cosim::LayerNetworkOptions run_lts_multi(const std::string& scenario,
                                                const std::filesystem::path& out,
                                                const std::string& transport, double safety,
                                                bool variable = false, bool lanes = true) {
  std::vector<std::string> argv{
      bin("crashlink"),       "run",   scenario,      "--mode",  "multi",
      "--coupling",           "lts",   "--transport", transport, "--step-safety",
      std::to_string(safety), "--out", out.string(),  "--quiet"};
  if (variable) argv.emplace_back("--variable-steps");
  if (!lanes) argv.emplace_back("--no-lanes");
  for (const auto& s : fast_session_args()) argv.push_back(s);
  Child run(argv);
  const auto st = run.wait(90s);
  EXPECT_TRUE(st.has_value()) << "crashlink run did not end within 90 s\n" << run.output();
  if (st) {
    EXPECT_EQ(exit_code(*st), 0) << run.output();
  }
  cosim::LayerNetworkOptions o;
  o.run.scheme = "lts";
  o.run.common_step = false;
  o.run.variable_steps = variable;
  o.step_safety = safety;
  return o;
}

// `lts` (issue #25) over processes: `crashlink run --mode multi --coupling lts` (ipc, lanes) is
// cosim::LayerNetwork with the lts form to the bit: every domain file's last state and the gathered
// result.h5 (its cut has the overlap layer, as the daemons' and the coordinator's).
TEST(LtsProcesses, MultiBarIsNetworkToTheBit) {
  const auto dir = fresh_dir("lts-multi-bar");
  const RemoveIfPassed cleanup{dir};
  std::string yaml = bar_yaml(6.0e-3);
  const std::string controls = "controls:\n";
  ASSERT_NE(yaml.find(controls), std::string::npos);
  yaml.insert(yaml.find(controls) + controls.size(), "  field_interval: 3.7e-4\n");  // off grid
  const std::string scenario = write_file(dir / "bar.yaml", yaml);
  const auto out = dir / "out";
  const auto o = run_lts_multi(scenario, out, "ipc", 0.9);  // crashlink run's default safety
  if (::testing::Test::HasFailure()) return;
  const auto m = io::read_scenario(scenario);
  const Reference ref = reference(m, o);
  ASSERT_EQ(ref.steps.size(), 2u);
  EXPECT_GT(std::max(ref.steps[0], ref.steps[1]), std::min(ref.steps[0], ref.steps[1]))
      << "one step for both: not multirate";
  const double worst = expect_network_bits(out, m, ref, {"fine", "coarse"}).worst;
  // The fine side's field states wait for an owner instant: between them its rim elements hold
  // their elastic trial (docs/multirate.md "Plasticity on the rim"); the coarse side's are at its
  // own instants. Both at or after each requested instant, the same count.
  {
    const coupling::Tick H = std::max(ref.steps[0], ref.steps[1]);
    const io::ResultReader fine((out / "domains" / "fine.h5").string());
    const io::ResultReader coarse((out / "domains" / "coarse.h5").string());
    ASSERT_GT(fine.state_count(), 10u);
    EXPECT_EQ(fine.state_count(), coarse.state_count());
    std::size_t off_grid = 0;
    for (std::size_t k = 0; k < fine.state_count(); ++k) {
      const auto t = static_cast<coupling::Tick>(
          std::llround(fine.state_time(k) * static_cast<double>(o.run.ticks_per_second)));
      EXPECT_EQ(t % H, 0) << "fine field state " << k << " at " << fine.state_time(k) << " s";
      if (k + 1 < fine.state_count()) {  // (the last: at the end, requested or not)
        EXPECT_GE(fine.state_time(k), 3.7e-4 * static_cast<double>(k) * (1.0 - 1e-9)) << k;
      }
      const double H_s = static_cast<double>(H) / static_cast<double>(o.run.ticks_per_second);
      off_grid += std::fmod(3.7e-4 * static_cast<double>(k), H_s) > 1e-12 ? 1 : 0;
    }
    EXPECT_GT(off_grid, 5u) << "the requested instants are owner instants: no test";
  }
  const auto g = last_state((out / "result.h5").string());
  const Diff gathered = compare(g, m, ref.u);
  EXPECT_EQ(gathered.max_abs, 0.0) << "gathered result.h5";
  std::printf(
      "[measured] lts multi over ipc, bar at H/h = %lld/%lld ticks: max |u - u_network| / "
      "max|u| = %.3e (domain files), %.3e (gathered, %zu nodes)\n",
      static_cast<long long>(std::max(ref.steps[0], ref.steps[1])),
      static_cast<long long>(std::min(ref.steps[0], ref.steps[1])), worst, gathered.rel(),
      gathered.nodes);

  // The scheme's energy (issue 25, build 2): each domain file's row holds its share at the last
  // coarse instant at or before the row's history instant, and that instant; result.h5 holds the
  // sum of the domains' shares of the same instant, the network's E at that instant.
  const auto fine_rows = io::ResultReader((out / "domains" / "fine.h5").string()).glstat();
  const auto coarse_rows = io::ResultReader((out / "domains" / "coarse.h5").string()).glstat();
  const auto rows = io::ResultReader((out / "result.h5").string()).glstat();
  ASSERT_GT(rows.size(), 3u);
  const auto& last = rows.back();
  ASSERT_TRUE(std::isfinite(last.scheme_energy_J));
  const double key = last.scheme_energy_time_s;
  auto share = [&](const std::vector<io::GlstatSample>& d) {
    for (const auto& r : d)
      if (r.scheme_energy_time_s == key) return r.scheme_energy_J;
    return std::numeric_limits<double>::quiet_NaN();
  };
  EXPECT_EQ(last.scheme_energy_J, share(fine_rows) + share(coarse_rows));
  std::size_t finite = 0;
  for (const auto& r : rows) finite += std::isfinite(r.scheme_energy_J) ? 1 : 0;
  EXPECT_GE(finite + 3, rows.size());  // NaN only before the third coarse instant
  cosim::LayerNetwork net(m, o);
  net.initialize();
  const auto at =
      static_cast<coupling::Tick>(std::llround(key * static_cast<double>(o.run.ticks_per_second)));
  net.run({}, at + 1);  // past the sample at `at`, before the next coarse instant's
  const double expected = net.lts_energy_J();
  EXPECT_NEAR(last.scheme_energy_J, expected, 1e-9 * std::abs(expected));
  std::printf(
      "[measured] lts scheme energy at the coarse instant %.4e s: result.h5 %.9e J, network "
      "%.9e J; %zu of %zu rows finite\n",
      key, last.scheme_energy_J, expected, finite, rows.size());
}

// A tree of three bars over processes under `crashlink run --mode multi --coupling lts` over tcp is
// LayerNetwork's lts run to the bit, and every row of result.h5 carries the network's summed E at
// its coarse instant. History rows every 10 us, past the coarsest step (about 3 us): each daemon
// samples its share only at the rows' coarse instants and the two before each
// (LayerStepper::set_lts_energy_wanted).
static void lts_tree_case(const std::string& label, const std::vector<BarPart>& parts) {
  const auto dir = fresh_dir("lts-" + label);
  const RemoveIfPassed cleanup{dir};
  std::string yaml = bar_parts_yaml(label, 2.11e-4, parts);
  const std::string key = "controls:\n";
  ASSERT_NE(yaml.find(key), std::string::npos);
  yaml.insert(yaml.find(key) + key.size(), "  history_interval: 1.0e-5\n");
  const std::string scenario = write_file(dir / (label + ".yaml"), yaml);
  const auto out = dir / "out";
  const auto o = run_lts_multi(scenario, out, "tcp", 0.8);
  if (::testing::Test::HasFailure()) return;
  const auto m = io::read_scenario(scenario);
  const Reference ref = reference(m, o);
  ASSERT_EQ(ref.steps.size(), 3u);
  std::vector<std::string> names;
  for (const auto& part : parts) names.push_back(part.name);
  const double bits = expect_network_bits(out, m, ref, names).worst;
  const Diff gathered = compare(last_state((out / "result.h5").string()), m, ref.u);
  EXPECT_EQ(gathered.max_abs, 0.0) << "gathered result.h5";
  // every row's summed share against the network's E at that coarse instant (sampled at all)
  const auto rows = io::ResultReader((out / "result.h5").string()).glstat();
  ASSERT_GT(rows.size(), 15u);
  cosim::LayerNetwork net(m, o);
  net.initialize();
  std::map<coupling::Tick, double> energy;
  std::size_t count = 0;
  net.run([&](std::size_t k) {
    if (net.stepper(k).time() % net.plan().base != 0) return;
    if (++count < net.size()) return;
    count = 0;
    energy[net.stepper(k).time()] = net.lts_energy_J();
  });
  std::size_t compared = 0;
  double worst = 0.0;
  for (const auto& r : rows) {
    if (!std::isfinite(r.scheme_energy_J)) continue;
    const auto at = static_cast<coupling::Tick>(
        std::llround(r.scheme_energy_time_s * static_cast<double>(o.run.ticks_per_second)));
    ASSERT_EQ(energy.count(at), 1u) << "row at " << r.time_s << " s: no coarse instant " << at;
    EXPECT_NEAR(r.scheme_energy_J, energy[at], 1e-12 * std::abs(energy[at])) << r.time_s;
    worst = std::max(worst, std::abs(r.scheme_energy_J / energy[at] - 1.0));
    ++compared;
  }
  EXPECT_GE(compared + 1, rows.size());  // NaN only in the first row (before the third instant)
  std::printf(
      "[measured] lts %s over tcp, steps %lld / %lld / %lld ticks: max |u - "
      "u_network| = %.3e (domain files), %.3e (gathered); summed E of %zu of %zu rows against the "
      "network's: max relative difference %.2e\n",
      label.c_str(), static_cast<long long>(ref.steps[0]), static_cast<long long>(ref.steps[1]),
      static_cast<long long>(ref.steps[2]), bits, gathered.max_abs, compared, rows.size(), worst);
}

// The chain: fine | mid | coarse (5 / 10 / 30 mm hexes; mid the fine side of coarse and the owner
// of fine).
TEST(LtsProcesses, ThreeDomainChainIsNetworkToTheBit) {
  lts_tree_case("chain3",
                {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}});
}

// One owner, two fine domains at different steps (fineA 5 mm, coarse 30 mm, fineB 10 mm hexes),
// and one fine domain with two owners at different steps (coarseA 40 mm, fine 5 mm, coarseB 30 mm).
TEST(LtsProcesses, StarTreesAreNetworkToTheBit) {
  lts_tree_case("star-owner",
                {{"fineA", 0.0, 0.1, 20}, {"coarse", 0.1, 0.3, 10}, {"fineB", 0.4, 0.2, 20}});
  lts_tree_case("star-fine",
                {{"coarseA", 0.0, 0.2, 5}, {"fine", 0.2, 0.1, 20}, {"coarseB", 0.3, 0.3, 10}});
}

// `lts` with variable steps over processes (crashlink run --coupling lts --variable-steps): each
// owner step rides one ahead on the u_J before it (LayerDisplacement.next_step_ticks). The bar over
// ipc with lanes; the chain fine | mid | coarse over tcp, whose middle domain announces its own
// steps once its owner's announcement is in; the chain with mid and coarse at one step (one
// substep per owner step: the Fbar leaves at the landing, and mid waits for the owner's next u_J
// in the cycle it takes the owner step up) through the coordinator (no lanes); one owner with two
// fine domains at different steps. Every domain file
// and result.h5 are LayerNetwork's to the bit, the steps changed during the run, and no row
// carries an lts E (variable steps have none).
TEST(LtsProcesses, VariableStepsAreNetworkToTheBit) {
  struct Case {
    std::string label, transport;
    std::vector<BarPart> parts;
    bool lanes = true;
  };
  const std::vector<Case> cases{
      {"bar", "ipc", {{"fine", 0.0, 0.3, 60}, {"coarse", 0.3, 0.3, 20}}},
      {"chain3", "tcp", {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 10}}},
      {"chain3-even",
       "tcp",
       {{"fine", 0.0, 0.1, 20}, {"mid", 0.1, 0.2, 20}, {"coarse", 0.3, 0.3, 28}},
       false},
      // one owner, two fine domains at different steps: the leader announces to both
      {"star-owner",
       "ipc",
       {{"fineA", 0.0, 0.1, 20}, {"coarse", 0.1, 0.3, 10}, {"fineB", 0.4, 0.2, 20}}}};
  for (const auto& c : cases) {
    const auto dir = fresh_dir("lts-variable-" + c.label);
    const RemoveIfPassed cleanup{dir};
    const std::string scenario = write_file(dir / (c.label + ".yaml"), [&] {
      // field states requested off the coarse instants (the fine side's wait for them)
      std::string yaml = bar_parts_yaml(c.label, 2.11e-4, c.parts);
      const std::string controls = "controls:\n";
      yaml.insert(yaml.find(controls) + controls.size(), "  field_interval: 1.37e-5\n");
      return yaml;
    }());
    const auto out = dir / "out";
    const auto o = run_lts_multi(scenario, out, c.transport, 0.9, true, c.lanes);
    if (::testing::Test::HasFailure()) return;
    const auto m = io::read_scenario(scenario);
    const Reference ref = reference(m, o);
    std::vector<std::string> names;
    for (const auto& part : c.parts) names.push_back(part.name);
    const auto bits = expect_network_bits(out, m, ref, names);
    const Diff gathered = compare(last_state((out / "result.h5").string()), m, ref.u);
    EXPECT_EQ(gathered.max_abs, 0.0) << c.label << ": gathered result.h5";
    // the steps changed: the coarse domain's instants are not evenly spaced
    cosim::LayerNetwork net(m, o);
    net.initialize();
    std::set<coupling::Tick> steps, instants;
    coupling::Tick last = -1;
    const std::size_t kc = [&] {
      for (std::size_t k = 0; k < net.size(); ++k)
        if (net.solver(k).domain_name() == "coarse") return k;
      return std::size_t{0};
    }();
    ASSERT_TRUE(net.run([&](std::size_t k) {
      if (k != kc) return;
      const auto t = net.stepper(k).time();
      if (last >= 0) steps.insert(t - last);
      instants.insert(t);
      last = t;
    }));
    EXPECT_GT(steps.size(), 1u) << c.label << ": the coarse step never changed";
    if (c.label == "bar") {  // the fine bar's field states sit on its owner's instants
      const io::ResultReader fine((out / "domains" / "fine.h5").string());
      ASSERT_GT(fine.state_count(), 10u);
      for (std::size_t k = 0; k < fine.state_count(); ++k) {
        const auto t = static_cast<coupling::Tick>(
            std::llround(fine.state_time(k) * static_cast<double>(o.run.ticks_per_second)));
        EXPECT_EQ(instants.count(t), 1u) << "fine field state " << k << " at " << t << " ticks";
      }
    }
    std::string cycles;
    for (std::size_t k = 0; k < net.size(); ++k)
      cycles += " " + net.solver(k).domain_name() + " " + std::to_string(net.solver(k).cycle());
    if (c.label == "chain3-even") {  // one substep per owner step between mid and coarse
      std::int64_t mid = 0, coarse = 0;
      for (std::size_t k = 0; k < net.size(); ++k) {
        if (net.solver(k).domain_name() == "mid") mid = net.solver(k).cycle();
        if (net.solver(k).domain_name() == "coarse") coarse = net.solver(k).cycle();
      }
      EXPECT_LE(mid, coarse + 2) << cycles;  // (the plan's first owner steps aside)
    }
    for (const auto& r : io::ResultReader((out / "result.h5").string()).glstat())
      EXPECT_FALSE(std::isfinite(r.scheme_energy_J)) << c.label << " row at " << r.time_s << " s";
    std::printf(
        "[measured] lts %s over %s%s, variable steps (%zu different coarse steps; cycles%s): "
        "max |u - u_network| = %.3e (domain files), %.3e (gathered)\n",
        c.label.c_str(), c.transport.c_str(), c.lanes ? "" : " without lanes", steps.size(),
        cycles.c_str(), bits.worst, gathered.max_abs);
  }
}

// `--mode split --variable-steps --coupling lts` is refused before any daemon starts: one common
// step is `layer`'s split.
TEST(LtsProcesses, SplitWithVariableStepsIsRefused) {
  const auto dir = fresh_dir("lts-split-variable");
  const RemoveIfPassed cleanup{dir};
  const std::string scenario = write_file(
      dir / "bar.yaml",
      bar_parts_yaml("bar", 2.11e-4, {{"fine", 0.0, 0.3, 60}, {"coarse", 0.3, 0.3, 20}}));
  std::vector<std::string> argv{
      bin("crashlink"), "run", scenario,           "--mode", "split",
      "--coupling",     "lts", "--variable-steps", "--out",  (dir / "out").string(),
      "--quiet"};
  for (const auto& s : fast_session_args()) argv.push_back(s);
  Child run(argv);
  const auto st = run.wait(90s);
  ASSERT_TRUE(st.has_value()) << run.output();
  EXPECT_NE(exit_code(*st), 0) << run.output();
  EXPECT_NE(run.output().find("one common step is `layer`'s split"), std::string::npos)
      << run.output();
}
