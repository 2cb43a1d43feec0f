#include "apps/cmd_gather.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>

#include "core/exit_codes.h"
#include "solver/daemon/domain_schemes.h"
#include "solver/gather/gather_results.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"

namespace crashlink::apps {

CLI::App* add_gather_command(CLI::App& app, GatherOptions& o) {
  auto* cmd = app.add_subcommand(
      "gather",
      "merge DIR/domains/*.h5 and DIR/coordinator.h5 of a coupled run into DIR/result.h5");
  cmd->add_option("scenario", o.scenario, "the scenario file the run used")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o.out, "the run's output directory")->capture_default_str();
  cmd->add_option("--coupling", o.coupling,
                  "the run's coupling scheme (its cut: lts moves more element layers)")
      ->check(CLI::IsMember(daemon::domain_scheme_names()))
      ->capture_default_str();
  return cmd;
}

int run_gather(const GatherOptions& o) {
  const auto model = io::read_scenario(o.scenario);
  const auto& entry = daemon::domain_scheme_named(o.coupling);
  const auto dec = partition::decompose(model, entry.cut, entry.overlap_layers);
  const auto r = gather::gather_results(model, dec, o.out);
  std::printf(
      "crashlink gather: %s/result.h5: %lld history rows up to t = %.6g s, %lld field "
      "states, from domain(s) '%s'\n",
      o.out.c_str(), static_cast<long long>(r.history_samples), r.end_time_s,
      static_cast<long long>(r.states),
      fmt::format("{}", fmt::join(r.domains_read, "', '")).c_str());
  for (const auto& n : r.notes) std::printf("note: %s\n", n.c_str());
  if (!r.missing.empty()) {
    std::fprintf(stderr,
                 "crashlink gather: missing or unusable: domain(s) '%s' (cut for --coupling %s: a "
                 "run with --coupling lts is gathered with --coupling lts)\n",
                 fmt::format("{}", fmt::join(r.missing, "', '")).c_str(), o.coupling.c_str());
    return kExitPeer;
  }
  return kExitOk;
}

}  // namespace crashlink::apps
