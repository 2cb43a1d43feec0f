#include "solver/run/run_single.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "solver/contact/contact_advice.h"
#include "solver/integration/solver.h"
#include "solver/io/result_writer.h"
#include "solver/model/run_estimate.h"
#include "solver/run/domain_recorder.h"
#include "solver/run/domain_timing.h"
#include "solver/run/mono_checkpoints.h"
#include "solver/run/progress.h"

namespace crashlink::run {

double RunSummary::ns_per_element_cycle() const {
  if (elements <= 0 || cycles <= 0) return 0.0;
  return 1e9 * cpu_seconds / (static_cast<double>(elements) * static_cast<double>(cycles));
}

RunSummary run_single_domain(const model::Model& model, const RunOptions& options) {
  const double wall0 = core::wall_seconds();
  const double cpu0 = core::process_cpu_seconds();
  RunSummary sum;
  sum.domain = options.domain_name;
  sum.elements = static_cast<std::int64_t>(model.element_count());
  sum.end_time_s = model.controls.end_time_s;

  MonoCheckpoints checkpoints(
      {options.out_dir, options.domain_name, options.scenario_hash, options.checkpoint_interval_s});
  // before the result file is opened (truncated): a refused restart leaves the folder as it was
  const std::int64_t restart_at = options.restart ? checkpoints.choose_restart() : -1;
  io::ResultWriter writer(options.out_dir, model);
  sum.result_h5 = writer.h5_path();
  sum.result_xdmf = writer.xdmf_path();
  integration::Solver solver(model, options.domain_name);
  solver.set_threads(options.threads);
  solver.set_step_hold(true);  // docs/elements.md "Step hold"
  sum.threads = options.threads;
  DomainRecorder recorder(writer, solver);
  double cpu_before = 0.0;  // of the runs before the checkpoint restarted from
  Progress progress(stderr, model.controls.end_time_s, options.progress);
  double setup_cpu_s = 0.0;  // before the first cycle
  try {
    solver.initialize();
    // What the run will cost, from the first stable step (model/run_estimate.h): an end time or a
    // mesh in the wrong unit shows here before hours are spent.
    if (options.progress)
      fmt::print(stderr, "{}: estimated {}\n", options.domain_name,
                 model::describe(model::estimate_run(model, solver.dt_s())));
    for (const auto& a : contact::advice(model))
      fmt::print(stderr, "{}: warning: {}\n", options.domain_name, a);
    if (options.restart) {
      cpu_before = checkpoints.restore(restart_at, recorder, solver);
    } else {
      checkpoints.start_fresh();
    }
    setup_cpu_s = core::process_cpu_seconds() - cpu0;
    for (;;) {
      solver.begin_cycle();  // state at t^n complete; guard passed
      recorder.sample();
      if (solver.finished()) break;
      if (options.stop != nullptr && options.stop->load()) {
        sum.stopped = true;
        break;
      }
      solver.end_cycle();
      if (checkpoints.enabled())
        checkpoints.after_cycle(recorder, solver, cpu_before + core::process_cpu_seconds() - cpu0);
      progress.update(solver.time_s(), solver.cycle(), solver.dt_s());
    }
    recorder.finish();  // also when stopped: the state at t^n passed the guard
  } catch (const NumericalError& e) {
    progress.finish();
    sum.failed = true;
    sum.failure = e.what();
    // The guard fired before the bad state was sampled: what is in the file is finite.
  }
  progress.finish();
  sum.cycles = solver.cycle();
  if (sum.stopped) sum.end_time_s = solver.time_s();
  sum.dt_min_s = solver.dt_min_s();
  sum.energy = solver.energy();
  for (std::size_t k = 0; k < model.contacts.size() && k < solver.contact_steps().size(); ++k)
    sum.contacts.push_back({model.contacts[k].name, solver.contact_steps()[k].energy_J});
  sum.weld_failures = solver.weld_failures();
  {
    std::vector<io::SpotWeldFailure> welds;
    for (const auto& w : sum.weld_failures)
      welds.push_back({w.name, w.time_s, w.normal_N, w.shear_N});
    writer.write_spot_weld_failures(welds);
  }
  sum.cpu_seconds = cpu_before + core::process_cpu_seconds() - cpu0;
  sum.wall_seconds = core::wall_seconds() - wall0;
  writer.write_timing(
      sum.wall_seconds, 0.0,
      {domain_timing(solver, options.domain_name, sum.cpu_seconds, sum.elements, setup_cpu_s)});
  writer.close();
  return sum;
}

void print_summary(std::FILE* out, const RunSummary& s) {
  std::fprintf(out, "\n%-12s %10s %10s %12s %10s %14s\n", "domain", "elements", "cycles",
               "dt_min [s]", "CPU [s]", "ns/elem/cycle");
  std::fprintf(out, "%-12s %10lld %10lld %12.4e %10.3f %14.1f\n", s.domain.c_str(),
               static_cast<long long>(s.elements), static_cast<long long>(s.cycles), s.dt_min_s,
               s.cpu_seconds, s.ns_per_element_cycle());
  std::fprintf(out, "coordinator: none (one domain); wall %.3f s; %d thread%s\n", s.wall_seconds,
               s.threads, s.threads == 1 ? "" : "s");
  const auto& e = s.energy;
  std::fprintf(out,
               "energy [J]: initial %.6g  kinetic %.6g  internal %.6g  hourglass %.6g  contact "
               "%.6g  external work %.6g  total %.6g\n",
               e.initial_total_J, e.kinetic_J, e.internal_J, e.hourglass_J, e.contact_J,
               e.external_work_J, e.total_J());
  const double hg_share = e.internal_J != 0.0 ? 100.0 * e.hourglass_J / e.internal_J : 0.0;
  print_energy_summary(out, {e.balance_J(), e.reference_J, s.contacts},
                       fmt::format("; hourglass {:.2f} % of internal", hg_share));
  if (!s.weld_failures.empty()) {
    // every weld that let go, the first ten named with when and what it carried
    std::fprintf(out, "spot welds failed: %zu\n", s.weld_failures.size());
    for (std::size_t k = 0; k < s.weld_failures.size() && k < 10; ++k) {
      const auto& w = s.weld_failures[k];
      std::fprintf(out, "  %s at t = %.6e s: tension %.4g N, shear %.4g N\n", w.name.c_str(),
                   w.time_s, w.normal_N, w.shear_N);
    }
    if (s.weld_failures.size() > 10)
      std::fprintf(out, "  ... and %zu more\n", s.weld_failures.size() - 10);
  }
  std::fprintf(out, "result: %s\n        %s\n", s.result_h5.c_str(), s.result_xdmf.c_str());
  if (s.failed) std::fprintf(out, "RUN FAILED: %s\n", s.failure.c_str());
  if (s.stopped)
    std::fprintf(out,
                 "STOPPED ON REQUEST at t = %.6e s (cycle %lld): the file holds the run up to "
                 "there\n",
                 s.end_time_s, static_cast<long long>(s.cycles));
}

}  // namespace crashlink::run
