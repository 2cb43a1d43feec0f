// crashlink: the user's command. Subcommands: run, hic, gather, compare, report, advise,
// stability-map.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/cmd_advise.h"
#include "apps/cmd_compare.h"
#include "apps/cmd_gather.h"
#include "apps/cmd_hic.h"
#include "apps/cmd_report.h"
#include "apps/cmd_run.h"
#include "apps/cmd_stability_map.h"
#include "apps/cmd_sweep.h"
#include "solver/core/errors.h"

int main(int argc, char** argv) {
  CLI::App app{"crashlink: multi-domain, multi-time-scale explicit dynamics for crash simulation"};
  app.require_subcommand(1);
  crashlink::apps::RunCommandOptions run_options;
  auto* run = crashlink::apps::add_run_command(app, run_options);
  crashlink::apps::HicOptions hic_options;
  auto* hic = crashlink::apps::add_hic_command(app, hic_options);
  crashlink::apps::GatherOptions gather_options;
  auto* gather = crashlink::apps::add_gather_command(app, gather_options);
  crashlink::apps::CompareOptions compare_options;
  auto* compare = crashlink::apps::add_compare_command(app, compare_options);
  crashlink::apps::ReportOptions report_options;
  auto* report = crashlink::apps::add_report_command(app, report_options);
  crashlink::apps::AdviseOptions advise_options;
  auto* advise = crashlink::apps::add_advise_command(app, advise_options);
  crashlink::apps::StabilityMapOptions map_options;
  auto* map = crashlink::apps::add_stability_map_command(app, map_options);
  crashlink::apps::SweepOptions sweep_options;
  auto* sweep = crashlink::apps::add_sweep_command(app, sweep_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (*run) return crashlink::apps::run_run(run_options);
    if (*hic) return crashlink::apps::run_hic(hic_options);
    if (*gather) return crashlink::apps::run_gather(gather_options);
    if (*compare) return crashlink::apps::run_compare(compare_options);
    if (*report) return crashlink::apps::run_report(report_options);
    if (*advise) return crashlink::apps::run_advise(advise_options);
    if (*map) return crashlink::apps::run_stability_map(map_options);
    if (*sweep) return crashlink::apps::run_sweep(sweep_options);
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
