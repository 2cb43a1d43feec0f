#pragma once
// `crashlink run SCENARIO [--out DIR] [--mode mono|split|multi] [--coupling layer|paper]
// [--transport ipc|tcp|inproc] [--quiet]` (DESIGN.md §4): runs the scenario, shows progress,
// prints the summary and, for every probe on a rigid body (a headform), HIC15 and HIC36 after
// CFC 1000 (the same output as `crashlink hic DIR/result.h5 --probe NAME`).
#include <CLI/CLI.hpp>
#include <string>

namespace crashlink::apps {

struct RunCommandOptions {
  std::string scenario;
  std::string out = "out";
  std::string mode = "mono";
  std::string coupling = "layer";
  std::string transport = "ipc";
  bool quiet = false;
};

CLI::App* add_run_command(CLI::App& app, RunCommandOptions& options);

/// Returns the exit code: 0, or 3 when the guard stopped the run (output kept). Errors throw.
int run_run(const RunCommandOptions& options);

}  // namespace crashlink::apps
