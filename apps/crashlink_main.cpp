// crashlink: the user's command. Subcommands: run, hic (more come with the co-simulation work).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "apps/cmd_hic.h"
#include "solver/core/errors.h"
#include "solver/io/scenario_reader.h"
#include "solver/run/run_single.h"

namespace {

int cmd_run(const std::string& scenario, const std::string& out, const std::string& mode,
            const std::string& coupling, const std::string& transport, bool quiet) {
  if (mode != "mono")
    throw crashlink::InputError(fmt::format(
        "--mode {}: only 'mono' (one domain) runs in this build; 'split' and 'multi' need the "
        "coordinator and daemons (co-simulation, not built yet)", mode));
  (void)coupling;
  (void)transport;
  const auto model = crashlink::io::read_scenario(scenario);
  std::printf("crashlink run: %s (%zu nodes, %zu elements, end time %.4g s) -> %s\n",
              model.name.c_str(), model.nodes.count(), model.element_count(),
              model.controls.end_time_s, out.c_str());
  std::fflush(stdout);
  crashlink::run::RunOptions opt;
  opt.out_dir = out;
  opt.progress = !quiet;
  const auto summary = crashlink::run::run_single_domain(model, opt);
  crashlink::run::print_summary(stdout, summary);
  if (summary.failed) {
    std::fprintf(stderr, "crashlink: error: %s\n", summary.failure.c_str());
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crashlink: multi-domain, multi-time-scale explicit dynamics for crash simulation"};
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a scenario locally and write DIR/result.h5");
  std::string scenario, out = "out", mode = "mono", coupling = "layer", transport = "ipc";
  bool quiet = false;
  run->add_option("scenario", scenario, "scenario YAML file")->required()->check(CLI::ExistingFile);
  run->add_option("--out", out, "output directory (result.h5, result.xdmf)");
  run->add_option("--mode", mode, "mono | split | multi")
      ->check(CLI::IsMember({"mono", "split", "multi"}));
  run->add_option("--coupling", coupling, "layer | paper")->check(CLI::IsMember({"layer", "paper"}));
  run->add_option("--transport", transport, "ipc | tcp | inproc")
      ->check(CLI::IsMember({"ipc", "tcp", "inproc"}));
  run->add_flag("--quiet", quiet, "no progress display");

  crashlink::apps::HicOptions hic_options;
  auto* hic = crashlink::apps::add_hic_command(app, hic_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (*run) return cmd_run(scenario, out, mode, coupling, transport, quiet);
    if (*hic) return crashlink::apps::run_hic(hic_options);
  } catch (const crashlink::InputError& e) {
    std::fprintf(stderr, "crashlink: input error: %s\n", e.what());
    return 2;
  } catch (const crashlink::Error& e) {
    std::fprintf(stderr, "crashlink: error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crashlink: internal error: %s\n", e.what());
    return 4;
  }
  return 0;
}
