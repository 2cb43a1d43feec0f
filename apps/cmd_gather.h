#pragma once
// `crashlink gather SCENARIO --out DIR` (docs/processes.md): merges the files of a coupled run
// (DIR/domains/<domain>.h5 of every daemon, DIR/coordinator.h5) into DIR/result.h5 and
// DIR/result.xdmf (solver/gather/gather_results.h). `crashlink run` does it by itself; this is for
// runs started by hand on several hosts, once their files are copied into one DIR.
#include <CLI/CLI.hpp>
#include <string>

namespace crashlink::apps {

struct GatherOptions {
  std::string scenario;
  std::string out = "out";
  std::string coupling = "layer";  ///< the run's --coupling: its cut (lts: overlap layers)
};

CLI::App* add_gather_command(CLI::App& app, GatherOptions& options);

/// Returns 0 when every domain's file was read, 5 (core/exit_codes.h kExitPeer) when some
/// were missing or short (what could be read is gathered). Errors throw.
int run_gather(const GatherOptions& options);

}  // namespace crashlink::apps
