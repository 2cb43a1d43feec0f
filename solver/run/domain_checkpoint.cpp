#include "solver/run/domain_checkpoint.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "solver/run/checkpoint_store.h"

namespace crashlink::run {

namespace fs = std::filesystem;

void write_domain_checkpoint(const DomainCheckpointSite& site, std::int64_t ticks, double time_s,
                             DomainRecorder& recorder, const integration::Solver& solver,
                             double cpu_seconds,
                             const std::function<void(core::StateWriter&)>& extra) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string dir = begin_checkpoint(site.out_dir, ticks, site.domain);
  recorder.flush();
  copy_into_checkpoint(recorder.writer().h5_path(), dir);
  core::StateWriter w;
  w.put_string("scenario_hash", site.scenario_hash);
  w.put_string("domain", site.domain);
  w.put_string("run.kind", site.kind);
  w.put_int("time_ticks", ticks);
  const auto sched = recorder.schedule();
  w.put_double("recorder.next_history_s", sched.next_history_s);
  w.put_double("recorder.next_field_s", sched.next_field_s);
  w.put_double("recorder.last_field_time_s", sched.last_field_time_s);
  w.put_double("run.cpu_seconds", cpu_seconds);
  solver.save_state(w);
  if (extra) extra(w);
  w.save((fs::path(dir) / "state.bin").string());
  commit_checkpoint(site.out_dir, ticks, site.domain, site.pieces);
  const double ms =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "%s: checkpoint at t = %.6e s (cycle %lld), %.1f MB of state, %.0f ms\n",
               site.log_prefix.c_str(), time_s, static_cast<long long>(solver.cycle()),
               static_cast<double>(w.bytes()) / 1e6, ms);
}

core::StateReader read_domain_checkpoint(const DomainCheckpointSite& site, std::int64_t ticks) {
  core::StateReader r(
      (fs::path(checkpoint_folder(site.out_dir, ticks, site.domain)) / "state.bin").string());
  // written before mono runs had checkpoints: a coupled run's
  const std::string kind = r.has("run.kind") ? r.get_string("run.kind") : kCoupledKind;
  if (r.get_string("scenario_hash") != site.scenario_hash ||
      r.get_string("domain") != site.domain || r.get_int("time_ticks") != ticks ||
      kind != site.kind) {
    throw CheckpointError(fmt::format(
        "checkpoint {}: written for domain '{}' of a {} run at {} ticks of scenario {}; this is "
        "domain '{}' of a {} run at {} ticks of scenario {}: restart with the scenario file and "
        "the --mode that wrote it",
        r.path(), r.get_string("domain"), kind, r.get_int("time_ticks"),
        r.get_string("scenario_hash"), site.domain, site.kind, ticks, site.scenario_hash));
  }
  return r;
}

DomainRestored restore_domain_checkpoint(
    const DomainCheckpointSite& site, std::int64_t ticks, double time_s, DomainRecorder& recorder,
    integration::Solver& solver, const std::function<void(const core::StateReader&)>& extra) {
  const core::StateReader r = read_domain_checkpoint(site, ticks);
  solver.restore_state(r);
  if (extra) extra(r);
  recorder.restore_schedule({r.get_double("recorder.next_history_s"),
                             r.get_double("recorder.next_field_s"),
                             r.get_double("recorder.last_field_time_s")});
  DomainRestored got;
  got.cpu_seconds = r.get_double("run.cpu_seconds");
  got.copied = io::replay_results((fs::path(checkpoint_folder(site.out_dir, ticks, site.domain)) /
                                   fs::path(recorder.writer().h5_path()).filename())
                                      .string(),
                                  recorder.writer(), solver.model(), solver.time_s());
  std::fprintf(stderr,
               "%s: restarted from the checkpoint at t = %.6e s (cycle %lld; %zu history rows and "
               "%zu field states kept)\n",
               site.log_prefix.c_str(), time_s, static_cast<long long>(solver.cycle()),
               got.copied.glstat_rows, got.copied.states);
  return got;
}

}  // namespace crashlink::run
