// crashlink-solver: one domain of a `layer` run as a daemon (solver/daemon/daemon.h,
// docs/processes.md). Started by `crashlink run` or by hand on any host:
//   crashlink-solver --connect tcp://host:port --domain NAME --scenario FILE --out DIR
// Exit codes: core/exit_codes.h (0 ok, 2 input, usage or refused, 3 guard, 4 internal, 5
// stopped because of another process or a socket failure). Defaults: apps/shared_defaults.h.
#pragma once

namespace crashlink::apps {

/// The whole program: parses the command line, runs, prints, returns the exit code. Its main() is
/// this call alone; a test's executable registers a scheme of its own first.
int solver_program(int argc, char** argv);

}  // namespace crashlink::apps
