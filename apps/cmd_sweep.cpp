#include "apps/cmd_sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "apps/cmd_run.h"
#include "apps/python_script.h"
#include "apps/result_head.h"
#include "apps/timing_reader.h"
#include "solver/core/errors.h"
#include "solver/cosim/split_advice.h"
#include "solver/integration/solver.h"
#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "solver/run/run_single.h"

namespace crashlink::apps {

namespace {

namespace fs = std::filesystem;

/// Conventional mass scaling of the fine parts (header). Returns the added mass [kg].
double mass_scale_fine_parts(model::Model& m) {
  const auto advice = cosim::survey_steps(m);
  const int fine_part = advice.finest_part();
  if (fine_part < 0) throw InputError("sweep: mass scaling needs deformable parts");
  // The fine domain: the one holding the part with the smallest step (all parts if none).
  std::vector<char> fine(m.parts.size(), 1);
  for (const auto& d : m.domains) {
    if (std::find(d.parts.begin(), d.parts.end(), fine_part) == d.parts.end())
      for (int p : d.parts) fine[static_cast<std::size_t>(p)] = 0;
  }
  double target = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    if (!fine[p] && !advice.parts[p].rigid) target = std::min(target, advice.parts[p].min_s);
  if (!std::isfinite(target)) {
    throw InputError(
        "sweep: mass scaling needs `domains:` with a coarse domain holding deformable parts");
  }
  const auto total_mass = [](const model::Model& model) {
    model::Model mono = model;
    mono.domains.clear();
    integration::Solver s(mono, "mass");
    s.initialize();
    return s.total_mass_kg();
  };
  const double mass_before = total_mass(m);
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const auto& ps = advice.parts[p];
    if (!fine[p] || ps.rigid || ps.min_s >= target) continue;
    const double f = (target / ps.min_s) * (target / ps.min_s);  // dt ~ 1/sqrt(rho)
    materials::Material scaled = m.materials[static_cast<std::size_t>(m.parts[p].material)];
    scaled.density_kg_m3 *= f;
    scaled.name.append("_mass_scaled");
    m.materials.push_back(scaled);
    m.parts[p].material = static_cast<int>(m.materials.size() - 1);
    std::printf("sweep: mass scaling of part '%s': density x %.3f (step %.4g -> %.4g s)\n",
                ps.name.c_str(), f, ps.min_s, target);
  }
  const double added = total_mass(m) - mass_before;
  std::printf("sweep: mass scaling adds %.4g kg to the model's %.4g kg\n", added, mass_before);
  return added;
}

struct Row {
  std::string name;
  double cpu_s = 0.0, wall_s = 0.0;
  double hic15 = 0.0, peak_g = 0.0, disp_m = 0.0;
  double added_mass_kg = 0.0;
  bool ok = false;
  std::string note;
};

void read_row(const std::string& h5, const std::string& disp_probe, Row& r) {
  const auto t = read_timing(h5);
  if (!t) {
    r.note = "no /timing: the run did not finish";
    return;
  }
  r.cpu_s = t->total_cpu_seconds();
  r.wall_s = t->wall_seconds;
  const io::ResultReader reader(h5);
  const std::string head = first_rigid_body_probe(reader);
  if (!head.empty()) {
    const auto m = result_head_metrics(reader, h5, head);
    r.hic15 = m.hic15.hic;
    r.peak_g = m.peak_g;
  }
  if (!disp_probe.empty()) {
    const auto p = reader.probe(disp_probe);
    for (std::size_t i = 0; i < p.size(); ++i)
      r.disp_m = std::max(r.disp_m, std::hypot(p.displacement_m[3 * i], p.displacement_m[3 * i + 1],
                                               p.displacement_m[3 * i + 2]));
  }
  r.ok = true;
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  auto* cmd = app.add_subcommand(
      "sweep", "speed-accuracy chart of a scene: mono, split, multi, mass scaling (CSV + PNG)");
  cmd->add_option("scenario", options.scenario, "scenario YAML file with `domains:`")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options.out, "output folder")->capture_default_str();
  cmd->add_option("--disp-probe", options.disp_probe,
                  "node probe whose peak displacement is compared (default: the first node probe)");
  return cmd;
}

int run_sweep(const SweepOptions& o) {
  const auto model = io::read_scenario(o.scenario);
  if (model.domains.size() < 2) {
    throw InputError(fmt::format(
        "sweep: {} has no `domains:` (at least two); `crashlink advise {}` proposes a split",
        o.scenario, o.scenario));
  }
  std::string disp_probe = o.disp_probe;
  if (disp_probe.empty()) {
    for (const auto& p : model.probes)
      if (disp_probe.empty() && p.kind == model::Probe::Kind::Node) disp_probe = p.name;
  }
  fs::create_directories(o.out);
  std::vector<Row> rows;
  int first_failure = 0;
  for (const char* mode : {"mono", "split", "multi"}) {
    RunCommandOptions r;
    r.scenario = o.scenario;
    r.out = (fs::path(o.out) / mode).string();
    r.mode = mode;
    r.quiet = true;
    std::printf("\nsweep: %s\n", mode);
    std::fflush(stdout);
    int rc = 0;
    try {
      rc = run_run(r);
    } catch (const Error& e) {
      std::fprintf(stderr, "sweep: %s failed: %s\n", mode, e.what());
      rc = 3;
    }
    Row row;
    row.name = mode;
    if (rc == 0) read_row(r.out + "/result.h5", disp_probe, row);
    if (rc != 0) row.note = fmt::format("exit code {}", rc);
    if (rc != 0 && first_failure == 0) first_failure = rc;
    rows.push_back(row);
  }
  {
    std::printf("\nsweep: mass_scaled\n");
    model::Model m = model;
    Row row;
    row.name = "mass_scaled";
    row.added_mass_kg = mass_scale_fine_parts(m);
    m.domains.clear();
    run::RunOptions ro;
    ro.out_dir = (fs::path(o.out) / "mass_scaled").string();
    ro.progress = false;
    const auto s = run::run_single_domain(m, ro);
    run::print_summary(stdout, s);
    if (s.failed) {
      row.note = s.failure;
      if (first_failure == 0) first_failure = 3;
    } else {
      read_row(s.result_h5, disp_probe, row);
    }
    rows.push_back(row);
  }

  const Row& ref = rows.front();
  auto err = [](double x, double r) { return r != 0.0 ? 100.0 * (x - r) / r : 0.0; };
  const fs::path csv = fs::path(o.out) / "sweep.csv";
  std::ofstream f(csv);
  f << "configuration,cpu_s,cpu_over_mono,wall_s,hic15,hic15_error_pct,peak_g,peak_error_pct,"
       "disp_max_m,disp_error_pct,added_mass_kg,note\n";
  std::printf("\n%-12s %9s %9s %9s %10s %8s %9s %8s %10s %8s\n", "config", "CPU [s]", "CPU/mono",
              "wall [s]", "HIC15", "err %", "peak [g]", "err %", "disp [mm]", "err %");
  for (const auto& r : rows) {
    if (!r.ok) {
      f << fmt::format("{},,,,,,,,,,,\"{}\"\n", r.name, r.note);
      std::printf("%-12s failed: %s\n", r.name.c_str(), r.note.c_str());
      continue;
    }
    const double ratio = ref.ok && ref.cpu_s > 0.0 ? r.cpu_s / ref.cpu_s : 0.0;
    f << fmt::format(
        "{},{:.4f},{:.4f},{:.4f},{:.2f},{:.4f},{:.3f},{:.4f},{:.6e},{:.4f},{:.4f},{}\n", r.name,
        r.cpu_s, ratio, r.wall_s, r.hic15, err(r.hic15, ref.hic15), r.peak_g,
        err(r.peak_g, ref.peak_g), r.disp_m, err(r.disp_m, ref.disp_m), r.added_mass_kg, r.note);
    std::printf("%-12s %9.2f %9.3f %9.2f %10.1f %+8.2f %9.1f %+8.2f %10.3f %+8.2f\n",
                r.name.c_str(), r.cpu_s, ratio, r.wall_s, r.hic15, err(r.hic15, ref.hic15),
                r.peak_g, err(r.peak_g, ref.peak_g), 1e3 * r.disp_m, err(r.disp_m, ref.disp_m));
  }
  f.close();
  std::printf("%s\n", csv.string().c_str());
  std::fflush(stdout);
  const int rc =
      run_python_script("sweep_chart.py", "CRASHLINK_SWEEP_SCRIPT",
                        {csv.string(), (fs::path(o.out) / "sweep.png").string()}, "sweep");
  if (rc != 0) return first_failure != 0 ? first_failure : rc;
  return first_failure;
}

}  // namespace crashlink::apps
