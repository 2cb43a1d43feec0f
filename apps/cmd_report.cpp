#include "apps/cmd_report.h"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "solver/core/errors.h"
#include "solver/io/result_reader.h"
#include "solver/signal/head_metrics.h"

namespace crashlink::apps {

namespace {

/// A shell word: 'text' with every ' written '\''.
std::string shell_word(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

/// tools/report.py of the source tree this binary was built from; CRASHLINK_REPORT_SCRIPT wins.
std::string report_script() {
  if (const char* env = std::getenv("CRASHLINK_REPORT_SCRIPT")) return env;
  return std::string(CRASHLINK_SOURCE_DIR) + "/tools/report.py";
}

}  // namespace

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
  std::string head_args;
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
    head_args = fmt::format(" --head {} --probe {} --hic {:.6g} --t1 {:.6g} --t2 {:.6g}",
                            shell_word(csv.string()), shell_word(probe), m.hic15.hic,
                            1e3 * m.hic15.t1_s, 1e3 * m.hic15.t2_s);
  }
  std::fflush(stdout);
  const std::string cmd =
      fmt::format("/usr/bin/python3 {} {} {}{}", shell_word(report_script()),
                  shell_word(options.result), shell_word(out.string()), head_args);
  const int status = std::system(cmd.c_str());
  if (status != 0) {
    std::fprintf(stderr,
                 "crashlink report: the plotting script failed (%s, status %d); it needs "
                 "/usr/bin/python3 with python3-matplotlib and python3-h5py "
                 "(tools/install-deps.sh installs them)\n",
                 report_script().c_str(), status);
    return 4;
  }
  return 0;
}

}  // namespace crashlink::apps
