// `crashlink run --mode split|multi` (cmd_run.h): launch, gather, summarise.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "apps/cmd_hic.h"
#include "apps/cmd_run.h"
#include "apps/launcher.h"
#include "apps/timing_reader.h"
#include "coordinator/coordinator_run.h"
#include "coordinator/coordinator_schemes.h"
#include "core/errors.h"
#include "core/exit_codes.h"
#include "coupling/coupling_config.h"
#include "solver/contact/contact_advice.h"
#include "solver/daemon/domain_schemes.h"
#include "solver/gather/gather_results.h"
#include "solver/gather/history_merge.h"
#include "solver/integration/mass_scaling.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "solver/materials/material.h"
#include "solver/model/run_estimate.h"
#include "solver/parallel/thread_shares.h"
#include "solver/parallel/thread_team.h"
#include "solver/partition/decomposition.h"
#include "solver/run/energy_summary.h"

namespace crashlink::apps {

namespace {

namespace fs = std::filesystem;

transport::Scheme scheme_of(const std::string& name) {
  if (name == "tcp") return transport::Scheme::tcp;
  if (name == "inproc") return transport::Scheme::inproc;
  return transport::Scheme::ipc;
}

/// What gathering DIR/domains/*.h5 and DIR/coordinator.h5 into DIR/result.h5 gave.
struct Gathered {
  bool written = false;     ///< DIR/result.h5 exists
  bool io_failure = false;  ///< the problem is a file that could not be written or read
  std::string problem;      ///< "" when every domain's file was merged completely
};

Gathered gather(const model::Model& model, const partition::Decomposition& dec,
                const std::string& out) {
  Gathered g;
  try {
    const auto r = gather::gather_results(model, dec, out);
    g.written = true;
    if (!r.missing.empty()) {
      g.problem =
          fmt::format("domain file(s) missing or unusable: '{}'", fmt::join(r.missing, "', '"));
    }
  } catch (const IoError& e) {
    g.problem = e.what();
    g.io_failure = true;
  } catch (const std::filesystem::filesystem_error& e) {
    g.problem = e.what();
    g.io_failure = true;
  } catch (const std::exception& e) {
    g.problem = e.what();
  }
  return g;
}

void print_timing(std::FILE* f, const TimingRecord& t, const LaunchResult& lr) {
  std::fprintf(f, "\n%-12s %10s %10s %12s %10s %14s %8s\n", "domain", "elements", "cycles",
               "dt_min [s]", "CPU [s]", "ns/elem/cycle", "threads");
  double sum_cpu = t.coordinator_cpu_seconds;
  for (const auto& d : t.domains) {
    const double ns = d.elements > 0 && d.cycles > 0
                          ? 1e9 * d.cpu_seconds /
                                (static_cast<double>(d.elements) * static_cast<double>(d.cycles))
                          : 0.0;
    std::fprintf(f, "%-12s %10lld %10lld %12.4e %10.3f %14.1f %8lld\n", d.name.c_str(),
                 static_cast<long long>(d.elements), static_cast<long long>(d.cycles), d.dt_min_s,
                 d.cpu_seconds, ns, static_cast<long long>(d.threads));
    sum_cpu += d.cpu_seconds;
  }
  double coordinator_cpu = t.coordinator_cpu_seconds;
  if (coordinator_cpu == 0.0 && !lr.pieces.empty()) {
    coordinator_cpu = lr.pieces.front().cpu_seconds;  // from wait4 when the file has none
    sum_cpu += coordinator_cpu;
  }
  std::fprintf(f, "coordinator: CPU %.3f s = %.2f %% of the total CPU %.3f s\n", coordinator_cpu,
               sum_cpu > 0.0 ? 100.0 * coordinator_cpu / sum_cpu : 0.0, sum_cpu);
  std::fprintf(f,
               "wall %.3f s vs sum of CPU times %.3f s: overlap %.2f (1 = the pieces took turns, "
               "%zu = all ran at once)\n",
               lr.wall_seconds, sum_cpu, lr.wall_seconds > 0.0 ? sum_cpu / lr.wall_seconds : 0.0,
               t.domains.size());
}

/// The scheme's conserved discrete energy (lts), summed over the domains in the gathered rows:
/// its first and last values and its largest relative change. Nothing for a scheme without one.
void print_scheme_energy(std::FILE* f, const std::vector<io::GlstatSample>& g) {
  const io::GlstatSample* first = nullptr;
  double worst = 0.0;
  for (const auto& row : g) {
    if (!std::isfinite(row.scheme_energy_J)) continue;
    if (first == nullptr) first = &row;
    if (first->scheme_energy_J != 0.0)
      worst = std::max(worst, std::abs(row.scheme_energy_J / first->scheme_energy_J - 1.0));
  }
  if (first == nullptr || !std::isfinite(g.back().scheme_energy_J)) return;
  std::fprintf(f,
               "lts invariant E (docs/multirate.md \"lts\") %.6g J at t = %.4e s, %.6g J at "
               "the end, largest |E/E_first - 1| %.2e: conserved by linear elastic models without "
               "loads or damping; with plasticity, contact or loads its u.K_H u part is no "
               "energy\n",
               first->scheme_energy_J, first->scheme_energy_time_s, g.back().scheme_energy_J,
               worst);
}

void print_energy(std::FILE* f, const model::Model& model, const std::string& h5, bool complete) {
  try {
    io::ResultReader reader(h5);
    const auto g = reader.glstat();
    if (g.empty()) return;
    const auto& e = g.back();
    std::fprintf(f,
                 "energy [J] at t = %.4e s: kinetic %.6g  internal %.6g  hourglass %.6g  contact "
                 "%.6g  external work %.6g  total %.6g\n",
                 e.time_s, e.kinetic_energy_J, e.internal_energy_J, e.hourglass_energy_J,
                 e.contact_energy_J, e.external_work_J, e.total_energy_J);
    // The coupling's own work: energy the scheme put in (> 0) or took out, as a share of the
    // energy the model had to carry: the larger of its initial total and the external work done
    // on it (a driven model starts at rest: a share of E0 = 0 would mean nothing).
    const double e0 = g.front().total_energy_J;
    const double scale = std::max(std::abs(e0), std::abs(e.external_work_J));
    std::fprintf(
        f, "coupling work %.6g J (%+.3f %% of the %s)\n", e.coupling_work_J,
        scale > 0.0 ? 100.0 * e.coupling_work_J / scale : 0.0,
        std::abs(e.external_work_J) > std::abs(e0) ? "external work" : "initial total energy");
    print_scheme_energy(f, g);
    // Each contact's energy: the last row of its domain's history (energy_summary.h).
    run::EnergySummary s;
    s.reference_J = gather::balance_reference_J(g);
    s.balance_J = e.energy_balance_error * s.reference_J;
    for (const auto& c : model.contacts) {
      double energy_J = std::numeric_limits<double>::quiet_NaN();  // not in the file: unknown
      try {
        const io::ContactHistory h = reader.contact(c.name);
        if (!h.energy_J.empty()) energy_J = h.energy_J.back();
      } catch (const Error&) {
      }
      s.contacts.push_back({c.name, energy_J});
    }
    run::print_energy_summary(
        f, s, complete ? "" : " (the run failed: some domains' histories are incomplete)");
  } catch (const std::exception& x) {
    std::fprintf(f, "energy: %s could not be read: %s\n", h5.c_str(), x.what());
  }
}

/// Threads per launched domain: --domain-threads NAME=N first; the others --threads, or with
/// --threads 0 the cores not given by name shared out by work, elements over the domain's stable
/// step as cut (parallel::share_threads: a coupled step waits for its slowest domain).
std::vector<int> domain_threads(const RunCommandOptions& o, const partition::Decomposition& dec,
                                const std::vector<std::string>& domains) {
  std::vector<int> out(domains.size(), 0);
  int given = 0;
  for (const auto& spec : o.domain_threads) {
    const auto eq = spec.find('=');
    const std::string name = spec.substr(0, eq);
    int n = 0;
    std::size_t used = 0;
    try {  // digits only: no sign, no blank
      if (eq != std::string::npos && eq + 1 < spec.size() &&
          std::isdigit(static_cast<unsigned char>(spec[eq + 1])))
        n = std::stoi(spec.substr(eq + 1), &used);
    } catch (const std::exception&) {
      n = 0;
    }
    if (eq == std::string::npos || used != spec.size() - eq - 1 || n < 1 || n > 1024)
      throw InputError(
          fmt::format("--domain-threads '{}': expected NAME=N with N in [1, 1024], e.g. {}=2", spec,
                      domains.empty() ? std::string("wiper") : domains.front()));
    const auto it = std::find(domains.begin(), domains.end(), name);
    if (it == domains.end())
      throw InputError(
          fmt::format("--domain-threads '{}': this run has no domain '{}'; its "
                      "domains: '{}'",
                      spec, name, fmt::join(domains, "', '")));
    auto& t = out[static_cast<std::size_t>(it - domains.begin())];
    if (t > 0) throw InputError(fmt::format("--domain-threads: domain '{}' is named twice", name));
    given += n;
    t = n;
  }
  std::vector<std::size_t> rest;
  std::vector<double> work;
  for (std::size_t k = 0; k < domains.size(); ++k) {
    if (out[k] > 0) continue;
    if (o.threads > 0) {
      out[k] = o.threads;
      continue;
    }
    // multi: elements x cycles ~ elements / own step; split: one common step, elements alone
    double w = 0.0;
    for (std::size_t i = 0; i < dec.domains.size(); ++i)
      if (dec.domains[i].name == domains[k] && i < dec.domain_dt_s.size() &&
          dec.domain_dt_s[i] > 0.0)
        w = static_cast<double>(dec.domains[i].model.element_count()) /
            (o.mode == "split" ? 1.0 : dec.domain_dt_s[i]);
    rest.push_back(k);
    work.push_back(w);
  }
  if (std::all_of(work.begin(), work.end(), [](double w) { return !(w > 0.0); }))
    std::fill(work.begin(), work.end(), 1.0);  // nothing to weigh by: evenly
  const int cores = parallel::available_cores();
  const auto shares = parallel::share_threads(work, cores - given);
  for (std::size_t j = 0; j < rest.size(); ++j) out[rest[j]] = shares[j];
  int total = 0;
  for (const int t : out) total += t;
  if (total > cores)
    std::fprintf(stderr,
                 "crashlink run: warning: %d solver threads on %d cores: the daemons will "
                 "share cores and wait for each other (--threads, --domain-threads)\n",
                 total, cores);
  return out;
}

}  // namespace

int run_coupled(const RunCommandOptions& o) {
  // The run's configuration, checked once before anything starts (coordinator::validate).
  coupling::CouplingConfig run;
  run.scheme = o.coupling;
  run.common_step = o.mode == "split";
  run.variable_steps = o.variable_steps;
  run.drift = !o.no_drift;
  run.checkpoint_interval_s = o.checkpoint_interval_s;
  run.restart = !o.restart.empty();
  run.lanes = !o.no_lanes;
  coordinator::validate(run);
  const auto model = io::read_scenario(o.scenario);
  if (model.controls.mass_scaling_dt_s > 0.0)
    std::printf("crashlink run: %s\n", integration::describe_mass_scaling(model).summary().c_str());
  if (run.scheme == "lts") {
    // The rim's rate terms still see the reflected path's velocity (docs/multirate.md "lts"):
    // one warning for the first such material, one for the first such part.
    const auto warn = [](const char* what, const std::string& name, const char* effect) {
      fmt::print(stderr,
                 "crashlink run: warning: --coupling lts with {} '{}': on the elements next to "
                 "the coupled nodes {} the reflected ghost path's velocity, not the motion's "
                 "(docs/multirate.md \"lts\"); --coupling layer has none\n",
                 what, name, effect);
    };
    for (const auto& mat : model.materials)
      if (mat.rate_dependent()) {
        warn("rate-dependent material", mat.name, "its strain rate is that of");
        break;
      }
    for (const auto& part : model.parts)
      if (part.damped()) {
        warn("damped part", part.name, "its damping is driven by");
        break;
      }
  }
  const auto& entry = daemon::domain_scheme_named(run.scheme);
  const auto dec = partition::decompose(model, entry.cut, entry.overlap_layers);
  std::vector<std::string> domains, emptied;
  for (const auto& d : dec.domains) {
    if (!d.empty()) {
      domains.push_back(d.name);
    } else {
      emptied.push_back(d.name);
    }
  }
  if (!model.domains.empty() && !emptied.empty()) {
    // The scenario has its domains; the cut left some without an element of their own.
    throw InputError(fmt::format(
        "--mode {}: the {} cut of {} leaves domain(s) '{}' empty: the fine side of an interface "
        "takes the coarse side's first layer of elements, and here that layer is the whole "
        "domain; give '{}' more than one element across the interface (a finer mesh or more "
        "parts), or merge it into its neighbour, or use --mode mono (`crashlink advise {}` "
        "shows the cuts that work)",
        o.mode, run.scheme, o.scenario, fmt::join(emptied, "', '"), fmt::join(emptied, "', '"),
        o.scenario));
  }
  if (domains.size() < 2) {
    throw InputError(fmt::format(
        "--mode {}: {} cuts into {} domain(s) ('{}'); split and multi couple two or more: give "
        "the scenario a `domains:` section (docs/scenario-format.md) or use --mode mono",
        o.mode, o.scenario, domains.size(), fmt::join(domains, "', '")));
  }
  std::printf(
      "crashlink run: %s (%zu nodes, %zu elements, end time %.4g s), --mode %s --coupling %s "
      "over %s: coordinator + %zu daemons ('%s') -> %s\n",
      model.name.c_str(), model.nodes.count(), model.element_count(), model.controls.end_time_s,
      o.mode.c_str(), o.coupling.c_str(), o.transport.c_str(), domains.size(),
      fmt::format("{}", fmt::join(domains, "', '")).c_str(), o.out.c_str());
  std::fflush(stdout);
  // What the run will cost at the smallest element step (model/run_estimate.h): an upper bound
  // for multi, whose coarse domains take fewer cycles.
  if (!o.quiet)
    fmt::print(stderr, "crashlink run: estimated {}\n",
               model::describe(model::estimate_run(model, model::estimated_stable_step_s(model))));
  for (const auto& a : contact::advice(model))
    fmt::print(stderr, "crashlink run: warning: {}\n", a);
  for (const auto& a : contact::domain_advice(model))
    fmt::print(stderr, "crashlink run: warning: {}\n", a);

  LaunchOptions lo;
  lo.scenario = o.scenario;
  lo.out_dir = o.out;
  lo.run = run;
  lo.scheme = scheme_of(o.transport);
  lo.progress = !o.quiet;
  lo.session = o.session;
  lo.join_timeout_ms = o.join_timeout_ms;
  lo.step_safety = o.step_safety;
  lo.threads = std::max(1, o.threads);
  lo.domain_threads = domain_threads(o, dec, domains);
  std::printf("crashlink run: threads per domain:");
  for (std::size_t k = 0; k < domains.size(); ++k)
    std::printf(" %s %d", domains[k].c_str(), lo.threads_of(k));
  const bool by_work = o.threads == 0 && o.domain_threads.size() < domains.size();
  std::printf("%s\n", by_work ? fmt::format(" ({} cores, the rest by work: {})",
                                            parallel::available_cores(),
                                            o.mode == "split" ? "elements" : "elements / step")
                                    .c_str()
                              : "");
  std::fflush(stdout);
  const LaunchResult lr = launch_local(lo, domains);

  const Gathered gathered = gather(model, dec, o.out);
  const std::string result_h5 = (fs::path(o.out) / "result.h5").string();
  std::optional<TimingRecord> timing;
  if (gathered.written) timing = read_timing(result_h5);
  if (!timing) {  // from the domains' own files
    TimingRecord t;
    for (const auto& d : domains) {
      if (auto one = read_timing((fs::path(o.out) / "domains" / (d + ".h5")).string())) {
        for (auto& x : one->domains) t.domains.push_back(std::move(x));
      }
    }
    timing = std::move(t);
  }
  print_timing(stdout, *timing, lr);
  if (gathered.written) {
    print_energy(stdout, model, result_h5, lr.ok() && gathered.problem.empty());
    std::printf("result: %s%s%s\n", result_h5.c_str(), gathered.problem.empty() ? "" : "; ",
                gathered.problem.c_str());
  } else {
    std::printf("result: not gathered: %s\n        the domains' files: %s/domains/*.h5\n",
                gathered.problem.c_str(), o.out.c_str());
  }

  if (lr.stopped_on_request) {
    std::fflush(stdout);
    std::fprintf(stderr,
                 "crashlink: stopped on request (SIGINT/SIGTERM): every piece stopped and flushed "
                 "its file; the results so far are in %s%s\n",
                 o.out.c_str(), gathered.written ? "/result.h5" : "/domains/*.h5");
    return kExitStopped;
  }
  if (lr.ok() && gathered.written && gathered.problem.empty()) {
    for (const auto& p : model.probes) {
      if (p.kind != model::Probe::Kind::RigidBody) continue;
      std::printf("\n");
      HicOptions h;
      h.file = result_h5;
      h.probe = p.name;
      h.cfc = "1000";
      run_hic(h);
    }
    return kExitOk;
  }
  std::fflush(stdout);
  if (lr.ok()) {
    std::fprintf(stderr, "crashlink: error: the run finished but gathering failed: %s\n",
                 gathered.problem.c_str());
    return gathered.io_failure ? kExitIo : kExitInternal;
  }
  // The code of the culprit: a piece that failed on its own, not one stopped because of another
  // (exit 5) or by the launcher after another failed; by priority the guard, a file, bad input, a
  // bug, a stop request (SIGTERM to one piece stops the others with exit 7 too).
  constexpr int kOwn[] = {kExitNumerical, kExitIo, kExitInput, kExitInternal, kExitStopped};
  std::vector<std::string> what;
  int code = kExitPeer;
  std::size_t rank = std::size(kOwn);
  for (const auto& p : lr.pieces) {
    if (p.ok()) continue;
    const std::string who = p.name == "coordinator" ? p.name : "domain '" + p.name + "'";
    PieceOutcome q = p;
    q.name = who;
    what.push_back(q.describe());
    if (p.killed_by_launcher) continue;
    for (std::size_t k = 0; k < rank; ++k) {
      if (p.exit_code == kOwn[k]) {
        rank = k;
        code = p.exit_code;
      }
    }
  }
  std::fprintf(stderr, "crashlink: error: the %s run failed: %s\n", o.mode.c_str(),
               fmt::format("{}", fmt::join(what, "; ")).c_str());
  return code;
}

}  // namespace crashlink::apps
