// crashlink-solver's command line and run (apps/solver_program.h).
#include "apps/solver_program.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "apps/program_cli.h"
#include "apps/session_flags.h"
#include "apps/shared_defaults.h"
#include "apps/stop_signal.h"
#include "core/exit_codes.h"
#include "solver/daemon/daemon.h"
#include "solver/daemon/domain_schemes.h"
#include "solver/parallel/thread_team.h"

namespace crashlink::apps {

int solver_program(int argc, char** argv) {
  CLI::App app{"crashlink-solver: one domain of a crashlink run, connected to the coordinator"};
  daemon::DaemonOptions o;
  o.out_dir = SharedDefaults::out;
  o.step_safety = SharedDefaults::step_safety;
  SessionFlags session;
  add_version_flag(app, "crashlink-solver");
  app.add_option("--connect", o.endpoint,
                 "the coordinator's endpoint: tcp://host:port, ipc://path or inproc://name")
      ->required();
  app.add_option("--domain", o.domain, "the domain to run (a name under the scenario's domains:)")
      ->required();
  app.add_option("--scenario", o.scenario, "scenario file (the same content as the coordinator's)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--out", o.out_dir, "output directory (writes DIR/domains/NAME.h5)")
      ->capture_default_str();
  app.add_option("--max-step", o.max_step_s,
                 "cap on the step this domain proposes, s (0: its stable step); for studies")
      ->check(CLI::NonNegativeNumber);
  bool no_lane = false;
  app.add_flag("--no-lane", no_lane,
               "offer no lane: the layer vectors go through the coordinator (a firewall that lets "
               "only the coordinator's port through; docs/processes.md \"Lanes\")");
  app.add_option("--step-safety", o.step_safety, "factor in (0, 1] on the proposed step")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  app.add_option("--threads", o.threads,
                 "threads computing this domain's element forces (0: every core this process "
                 "may use); the results are the same to the bit for every count")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  std::string coupling = SharedDefaults::coupling;
  add_coupling_option(app, coupling, daemon::domain_scheme_names(),
                      "the coupling scheme; the coordinator's must be the same");
  add_session_flags(app, session);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error_exit(app, e, "crashlink-solver");
  }
  o.session = session.options();
  o.offer_lane = !no_lane;
  o.coupling = coupling;
  if (o.threads == 0) o.threads = parallel::available_cores();
  install_stop_handlers();
  o.stop = &stop_flag();
  const auto r = daemon::run_daemon(o);
  if (r.exit_code != 0) std::fprintf(stderr, "crashlink-solver: error: %s\n", r.message.c_str());
  return r.exit_code;
}

}  // namespace crashlink::apps
