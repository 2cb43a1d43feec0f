#include "apps/cmd_report.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "apps/python_script.h"
#include "solver/core/errors.h"
#include "solver/io/result_reader.h"
#include "solver/signal/head_metrics.h"

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
  std::string probe = options.probe;
  io::ResultReader reader(options.result);
  if (probe.empty()) {
    for (const auto& name : reader.probe_names()) {
      if (reader.probe(name).kind == "rigid_body") {
        probe = name;
        break;
      }
    }
  }
  std::vector<std::string> args{options.result, out.string()};
  if (!probe.empty()) {
    const io::ProbeHistory p = reader.probe(probe);
    const signal::HeadMetrics m = signal::head_metrics_xyz(
        p.time_s, p.acceleration_m_s2, 1000, fmt::format("{}, probe '{}'", options.result, probe));
    const fs::path csv = out / "head_cfc1000.csv";
    std::ofstream f(csv);
    f << "time_ms,accel_g\n";
    for (std::size_t i = 0; i < m.time_s.size(); ++i)
      f << fmt::format("{:.6f},{:.6g}\n", 1e3 * m.time_s[i], m.accel_g[i]);
    f.close();
    if (!f) throw InputError(fmt::format("report: cannot write {}", csv.string()));
    std::printf("%s\n", csv.string().c_str());
    for (auto& a : std::vector<std::string>{"--head", csv.string(), "--probe", probe, "--hic",
                                            fmt::format("{:.6g}", m.hic15.hic), "--t1",
                                            fmt::format("{:.6g}", 1e3 * m.hic15.t1_s), "--t2",
                                            fmt::format("{:.6g}", 1e3 * m.hic15.t2_s)})
      args.push_back(std::move(a));
  }
  return run_python_script("report.py", "CRASHLINK_REPORT_SCRIPT", args, "report");
}

}  // namespace crashlink::apps
