// crashlink-coordinator's command line and run (apps/coordinator_program.h).
#include "apps/coordinator_program.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <string>

#include "apps/program_cli.h"
#include "apps/session_flags.h"
#include "apps/shared_defaults.h"
#include "apps/stop_signal.h"
#include "coordinator/coordinator_run.h"
#include "coordinator/coordinator_schemes.h"
#include "core/exit_codes.h"
#include "solver/run/progress.h"

namespace crashlink::apps {

int coordinator_program(int argc, char** argv) {
  CLI::App app{"crashlink-coordinator: couples the domains of a crashlink run"};
  coordinator::CoordinatorOptions o;
  o.out_dir = SharedDefaults::out;
  o.run.checkpoint_interval_s = SharedDefaults::checkpoint_interval_s;
  SessionFlags session;
  std::string mode = SharedDefaults::coupled_mode;
  int join_timeout_ms = SharedDefaults::join_timeout_ms;
  add_version_flag(app, "crashlink-coordinator");
  bool progress = false;
  app.add_option("--bind", o.bind,
                 "endpoint to bind: tcp://HOST:PORT (PORT * or 0: any free port, printed), "
                 "ipc://PATH, inproc://NAME")
      ->required();
  app.add_option("--scenario", o.scenario, "scenario file")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out_dir, "output directory (writes DIR/coordinator.h5)")
      ->capture_default_str();
  app.add_option("--mode", mode, "split (one common step) | multi (each domain its own step)")
      ->check(CLI::IsMember({"split", "multi"}))
      ->capture_default_str();
  app.add_option("--endpoint-file", o.endpoint_file,
                 "write the bound endpoint (with the real port) to this file once listening");
  app.add_option("--join-timeout-ms", join_timeout_ms,
                 "every domain must have joined and registered within this time, ms (a daemon "
                 "silent for --timeout-ms before its Register is dropped: its domain may join "
                 "again until then)")
      ->check(CLI::Range(1, 86400000))
      ->capture_default_str();
  app.add_flag("--progress", progress, "progress line on stderr (the slowest domain's time)");
  app.add_option("--checkpoint-interval", o.run.checkpoint_interval_s,
                 "write checkpoints (all domains) every this much simulated time, s, rounded to a "
                 "multiple of every domain's step; 0: none")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  bool no_lanes = false;
  app.add_flag("--no-lanes", no_lanes,
               "route the layer vectors through the coordinator even where the daemons offer "
               "lanes (daemon to daemon; docs/processes.md \"Lanes\")");
  app.add_flag("--restart", o.run.restart,
               "resume from the newest checkpoint in --out that every domain has (the daemons "
               "list theirs when they register)");
  std::string coupling = SharedDefaults::coupling;
  add_coupling_option(app, coupling, coordinator::coordinator_scheme_names(),
                      "the coupling scheme, every daemon's too (paper: Bourel 2005 [8]-[11], no "
                      "checkpoints)");
  bool no_drift = false;
  app.add_flag("--no-drift", no_drift, "`paper`: drift correction [11] off (the study's S2)");
  app.add_flag(
      "--variable-steps", o.run.variable_steps,
      "variable steps instead of fixed steps planned at the start. `paper`: impose each free "
      "state's own step proposal (split: the smallest of all at every instant; multi: each its "
      "own); `layer`: the same, the leader choosing the step from its own and its holders' "
      "proposals (docs/multirate.md)");
  add_session_flags(app, session);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error_exit(app, e, "crashlink-coordinator");
  }
  o.run.common_step = mode == "split";
  o.run.lanes = !no_lanes;
  o.run.scheme = coupling;
  o.run.drift = !no_drift;
  o.session = session.options();
  o.join_timeout = std::chrono::milliseconds{join_timeout_ms};
  install_stop_handlers();
  o.stop = &stop_flag();
  std::optional<run::Progress> bar;
  if (progress) {
    o.on_progress = [&](double t_s, double end_s, const std::string& slowest) {
      if (!bar) bar.emplace(stderr, end_s, true);
      bar->update(t_s, "slowest: " + slowest);
    };
  }
  const auto r = coordinator::run_coordinator(o);
  if (bar) bar->finish();
  for (const auto& d : r.domains) {
    std::fprintf(stderr,
                 "crashlink-coordinator: domain '%s': %s, %lld cycles, CPU %.3f s, waited %.3f s\n",
                 d.name.c_str(), d.finished ? "finished" : "did not finish",
                 static_cast<long long>(d.cycles), d.cpu_seconds, d.wait_seconds);
  }
  if (r.exit_code != 0) {
    std::fprintf(stderr, "crashlink-coordinator: error: %s\n", r.message.c_str());
  } else {
    std::fprintf(stderr, "crashlink-coordinator: done: %s, %lld reports, CPU %.3f s, wall %.3f s\n",
                 r.lanes ? "layer vectors daemon to daemon (lanes)"
                         : fmt::format("{} layer vectors routed", r.messages_forwarded).c_str(),
                 static_cast<long long>(r.reports), r.cpu_seconds, r.wall_seconds);
  }
  return r.exit_code;
}

}  // namespace crashlink::apps
