// crashlink-solver: one domain of a `layer` run as a daemon (solver/daemon/daemon.h,
// docs/processes.md). Started by `crashlink run` or by hand on any host:
//   crashlink-solver --connect tcp://host:port --domain NAME --scenario FILE --out DIR
// Exit codes: core/exit_codes.h (0 ok, 2 input, usage or refused, 3 guard, 4 internal, 5
// stopped because of another process or a socket failure). Defaults: apps/shared_defaults.h.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "apps/program_cli.h"
#include "apps/session_flags.h"
#include "apps/shared_defaults.h"
#include "apps/stop_signal.h"
#include "core/exit_codes.h"
#include "solver/daemon/daemon.h"

int main(int argc, char** argv) {
  using namespace crashlink;
  CLI::App app{"crashlink-solver: one domain of a crashlink run, connected to the coordinator"};
  daemon::DaemonOptions o;
  o.out_dir = apps::SharedDefaults::out;
  o.step_safety = apps::SharedDefaults::step_safety;
  apps::SessionFlags session;
  apps::add_version_flag(app, "crashlink-solver");
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
  std::string coupling = apps::SharedDefaults::coupling;
  app.add_option("--coupling", coupling,
                 "layer (default) | paper: the coupling scheme; the coordinator's must be the same")
      ->check(CLI::IsMember({"layer", "paper"}))
      ->capture_default_str();
  apps::add_session_flags(app, session);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return apps::parse_error_exit(app, e, "crashlink-solver");
  }
  o.session = session.options();
  o.offer_lane = !no_lane;
  o.coupling = coupling;
  apps::install_stop_handlers();
  o.stop = &apps::stop_flag();
  const auto r = daemon::run_daemon(o);
  if (r.exit_code != 0) std::fprintf(stderr, "crashlink-solver: error: %s\n", r.message.c_str());
  return r.exit_code;
}
