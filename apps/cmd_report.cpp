#include "apps/cmd_report.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "apps/contact_force_csv.h"
#include "apps/python_script.h"
#include "apps/result_head.h"
#include "core/errors.h"

namespace crashlink::apps {

CLI::App* add_report_command(CLI::App& app, ReportOptions& options) {
  auto* cmd = app.add_subcommand(
      "report", "PNGs of a result: head acceleration + HIC, energy balance, drift, contacts");
  cmd->add_option("result", options.result, "result.h5 of a run")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options.out, "folder of the PNGs (default: RESULT's folder/report)");
  cmd->add_option("--probe", options.probe, "head probe (default: the first rigid-body probe)");
  return cmd;
}

int run_report(const ReportOptions& options) {
  namespace fs = std::filesystem;
  const fs::path out = options.out.empty() ? fs::absolute(options.result).parent_path() / "report"
                                           : fs::path(options.out);
  fs::create_directories(out);
  const io::ResultReader reader(options.result);
  const std::string probe = options.probe.empty() ? first_rigid_body_probe(reader) : options.probe;
  std::vector<std::string> args{options.result, out.string()};
  if (!probe.empty()) {
    const signal::HeadMetrics m = result_head_metrics(reader, options.result, probe);
    const fs::path csv = out / "head_cfc1000.csv";
    write_head_csv(csv.string(), m, "report");
    std::printf("%s\n", csv.string().c_str());
    for (auto& a : std::vector<std::string>{"--head", csv.string(), "--probe", probe, "--hic",
                                            fmt::format("{:.6g}", m.hic15.hic), "--t1",
                                            fmt::format("{:.6g}", 1e3 * m.hic15.t1_s), "--t2",
                                            fmt::format("{:.6g}", 1e3 * m.hic15.t2_s)})
      args.push_back(std::move(a));
  }
  if (!reader.contact_names().empty()) {
    const fs::path csv = out / "contact_forces_cfc180.csv";
    write_contact_force_csv(csv.string(), reader, "report");
    std::printf("%s\n", csv.string().c_str());
    args.push_back("--contacts");
    args.push_back(csv.string());
  }
  return run_python_script("report.py", "CRASHLINK_REPORT_SCRIPT", args, "report");
}

}  // namespace crashlink::apps
