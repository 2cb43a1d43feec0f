// crashlink-coordinator: the coordinator of a `layer` run (coordinator/coordinator_run.h,
// docs/processes.md). Started by `crashlink run` or by hand:
//   crashlink-coordinator --bind tcp://0.0.0.0:5555 --scenario FILE --out DIR [--mode multi]
// It prints the bound endpoint (and writes it to --endpoint-file), waits for one daemon per
// domain, runs, and writes DIR/coordinator.h5. Exit codes: core/exit_codes.h. Defaults:
// apps/shared_defaults.h.
#pragma once

namespace crashlink::apps {

/// The whole program: parses the command line, runs, prints, returns the exit code. Its main() is
/// this call alone; a test's executable registers a scheme of its own first.
int coordinator_program(int argc, char** argv);

}  // namespace crashlink::apps
