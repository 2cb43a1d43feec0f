// crashlink: the user's command. Subcommands: run, hic, gather, compare, report, advise,
// stability-map, sweep, keygen, export. A usage error (any subcommand, or none) exits 2 with
// CLI11's message (apps/program_cli.h); --help and --version exit 0.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "apps/cmd_advise.h"
#include "apps/cmd_compare.h"
#include "apps/cmd_export.h"
#include "apps/cmd_gather.h"
#include "apps/cmd_hic.h"
#include "apps/cmd_keygen.h"
#include "apps/cmd_report.h"
#include "apps/cmd_run.h"
#include "apps/cmd_stability_map.h"
#include "apps/cmd_sweep.h"
#include "apps/program_cli.h"
#include "core/errors.h"
#include "core/exit_codes.h"

int main(int argc, char** argv) {
  CLI::App app{"crashlink: multi-domain, multi-time-scale explicit dynamics for crash simulation"};
  app.require_subcommand(1);
  crashlink::apps::add_version_flag(app, "crashlink");
  namespace cl = crashlink::apps;
  // Each subcommand: its options (filled by the parse) and the function that runs it.
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands;
  auto add = [&](auto& options, auto add_command, auto run_command) {
    commands.emplace_back(add_command(app, options),
                          [&options, run_command] { return run_command(options); });
  };
  cl::RunCommandOptions run_options;
  cl::HicOptions hic_options;
  cl::GatherOptions gather_options;
  cl::CompareOptions compare_options;
  cl::ReportOptions report_options;
  cl::AdviseOptions advise_options;
  cl::StabilityMapOptions map_options;
  cl::SweepOptions sweep_options;
  cl::KeygenOptions keygen_options;
  cl::ExportOptions export_options;
  add(run_options, cl::add_run_command, cl::run_run);
  add(hic_options, cl::add_hic_command, [](const cl::HicOptions& o) { return cl::run_hic(o); });
  add(gather_options, cl::add_gather_command, cl::run_gather);
  add(compare_options, cl::add_compare_command, cl::run_compare);
  add(report_options, cl::add_report_command, cl::run_report);
  add(advise_options, cl::add_advise_command,
      [](const cl::AdviseOptions& o) { return cl::run_advise(o); });
  add(map_options, cl::add_stability_map_command, cl::run_stability_map);
  add(sweep_options, cl::add_sweep_command, cl::run_sweep);
  add(keygen_options, cl::add_keygen_command, cl::run_keygen);
  add(export_options, cl::add_export_command,
      [](const cl::ExportOptions& o) { return cl::run_export(o); });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // No subcommand: `crashlink` alone prints the usage; `crashlink frob` names what it got.
    // Either exits 2 as any usage error.
    std::string what;
    if (app.get_subcommands().empty() && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      const auto got = app.remaining();
      if (got.empty()) {
        std::fputs(app.help().c_str(), stderr);
      } else {
        std::vector<std::string> names;
        for (const auto& [command, run_command] : commands) names.push_back(command->get_name());
        what =
            fmt::format("'{}' is not {}; the subcommands: {}", got.front(),
                        got.front().starts_with('-') ? "an option of crashlink without a subcommand"
                                                     : "a subcommand",
                        fmt::join(names, ", "));
      }
    }
    return crashlink::apps::parse_error_exit(app, e, "crashlink", what);
  }
  try {
    for (const auto& [command, run_command] : commands)
      if (*command) return run_command();
  } catch (const crashlink::InputError& e) {
    std::fprintf(stderr, "crashlink: input error: %s\n", e.what());
    return crashlink::kExitInput;
  } catch (const crashlink::ModelError& e) {
    // a model the run cannot take (e.g. its decomposition): bad input, as the daemons report it
    std::fprintf(stderr, "crashlink: model error: %s\n", e.what());
    return crashlink::kExitInput;
  } catch (const crashlink::IoError& e) {
    std::fprintf(stderr, "crashlink: I/O error: %s\n", e.what());
    return crashlink::kExitIo;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "crashlink: I/O error: %s\n", e.what());
    return crashlink::kExitIo;
  } catch (const crashlink::Error& e) {
    std::fprintf(stderr, "crashlink: error: %s\n", e.what());
    return crashlink::kExitNumerical;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crashlink: internal error: %s\n", e.what());
    return crashlink::kExitInternal;
  }
  return 0;
}
