#include "apps/cmd_sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "apps/cmd_run.h"
#include "apps/python_script.h"
#include "apps/result_head.h"
#include "apps/scenario_variant.h"
#include "apps/sweep_paper.h"
#include "apps/timing_reader.h"
#include "core/errors.h"
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
  std::string reference = "mono";  ///< the row its CPU ratio and errors are against
  double step_ratio = 0.0;         ///< coarsest over finest domain step (element steps)
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

/// Largest over smallest of the domains' smallest element steps (0 without two deformable domains).
double step_ratio(const model::Model& m) {
  const auto survey = cosim::survey_steps(m);
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const auto& d : m.domains) {
    double dmin = std::numeric_limits<double>::infinity();
    for (int p : d.parts) {
      const auto& ps = survey.parts[static_cast<std::size_t>(p)];
      if (!ps.rigid) dmin = std::min(dmin, ps.min_s);
    }
    if (!std::isfinite(dmin)) continue;
    lo = std::min(lo, dmin);
    hi = std::max(hi, dmin);
  }
  return std::isfinite(lo) && lo > 0.0 ? hi / lo : 0.0;
}

/// --refine PART=N1,N2: the part and the division counts.
std::pair<std::string, std::vector<int>> parse_refine(const std::string& spec) {
  const auto eq = spec.find('=');
  auto bad = [&] {
    return InputError(
        fmt::format("sweep: --refine '{}': expected PART=N1,N2,... (a part with a "
                    "generated mesh and its new `divisions:`, whole numbers >= 1)",
                    spec));
  };
  if (eq == std::string::npos || eq == 0) throw bad();
  std::vector<int> n;
  std::stringstream ss(spec.substr(eq + 1));
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    std::size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(cell, &used);
    } catch (const std::exception&) {
      throw bad();
    }
    if (used != cell.size() || v < 1) throw bad();
    n.push_back(v);
  }
  if (n.empty()) throw bad();
  return {spec.substr(0, eq), n};
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  auto* cmd = app.add_subcommand(
      "sweep",
      "speed-accuracy chart of a scene: mono, split, multi, lts, paper, mass scaling (CSV + PNG)");
  cmd->add_option("scenario", options.scenario, "scenario YAML file with `domains:`")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options.out, "output folder")->capture_default_str();
  cmd->add_option("--disp-probe", options.disp_probe,
                  "node probe whose peak displacement is compared (default: the first node probe)");
  cmd->add_option("--refine", options.refine,
                  "PART=N1,N2,...: also the scene with PART's generated mesh at `divisions: N` "
                  "(mono and multi each; e.g. wiper_bar=100,200 for larger step ratios)");
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
  const double base_ratio = step_ratio(model);
  auto run_mode = [&](const std::string& scenario, const std::string& mode, const std::string& name,
                      const std::string& reference, double ratio,
                      const std::string& coupling = SharedDefaults::coupling) {
    RunCommandOptions r;
    r.scenario = scenario;
    r.out = (fs::path(o.out) / name).string();
    r.mode = mode;
    r.coupling = coupling;
    r.quiet = true;
    std::printf("\nsweep: %s\n", name.c_str());
    std::fflush(stdout);
    int rc = 0;
    try {
      rc = run_run(r);
    } catch (const Error& e) {
      std::fprintf(stderr, "sweep: %s failed: %s\n", name.c_str(), e.what());
      rc = 3;
    }
    Row row;
    row.name = name;
    row.reference = reference;
    row.step_ratio = ratio;
    if (rc == 0) read_row(r.out + "/result.h5", disp_probe, row);
    if (rc != 0) row.note = fmt::format("exit code {}", rc);
    if (rc != 0 && first_failure == 0) first_failure = rc;
    rows.push_back(row);
  };
  for (const char* mode : {"mono", "split", "multi"})
    run_mode(o.scenario, mode, mode, "mono", base_ratio);
  // the energy-conserving multirate scheme (issue 25) over processes, as multi
  run_mode(o.scenario, "multi", "lts", "mono", base_ratio, "lts");
  // The seed's scheme at multi's ratio (apps/sweep_paper.h): where it goes unstable, its guard
  // stops it and the row says when; that is the scheme's result, not a failure of the sweep.
  for (const bool drift : {true, false}) {
    const std::string name = drift ? "paper" : "paper_no_drift";
    std::printf("\nsweep: %s (in this process)\n", name.c_str());
    std::fflush(stdout);
    std::string head;
    for (const auto& p : model.probes)
      if (head.empty() && p.kind == model::Probe::Kind::RigidBody) head = p.name;
    const auto pr = run_paper_scene(model, drift, head, disp_probe);
    Row row;
    row.name = name;
    row.step_ratio = base_ratio;
    row.cpu_s = pr.cpu_s;
    row.wall_s = pr.wall_s;
    row.hic15 = pr.hic15;
    row.peak_g = pr.peak_g;
    row.disp_m = pr.disp_m;
    row.ok = pr.finished;
    const std::string gaps = fmt::format("largest gap link {:.3g} m, copy {:.3g} m",
                                         pr.max_link_gap_m, pr.max_copy_gap_m);
    row.note = pr.finished ? fmt::format("H/h = {:g}; {}", pr.ratio, gaps)
                           : fmt::format("H/h = {:g}; {}; stopped after {:.3f} ms: {}", pr.ratio,
                                         gaps, 1e3 * pr.stopped_at_s, pr.stopped.substr(0, 200));
    std::printf("sweep: %s: %s\n", name.c_str(), row.note.c_str());
    rows.push_back(row);
  }
  {
    std::printf("\nsweep: mass_scaled\n");
    model::Model m = model;
    Row row;
    row.name = "mass_scaled";
    row.step_ratio = 1.0;
    row.added_mass_kg = mass_scale_fine_parts(m);
    m.domains.clear();
    run::RunOptions ro;
    ro.out_dir = (fs::path(o.out) / "mass_scaled").string();
    ro.progress = false;
    const auto s = run::run_single_domain(m, ro);
    run::print_summary(stdout, s);
    if (s.failed) {
      // The solver's guard stopped it: the configuration's result (as the paper rows'), shown in
      // its row and under the chart, not a failure of the sweep.
      row.note = "stopped by the guard: " + s.failure;
    } else {
      read_row(s.result_h5, disp_probe, row);
    }
    rows.push_back(row);
  }

  if (!o.refine.empty()) {
    const auto [part, divisions] = parse_refine(o.refine);
    for (const int n : divisions) {
      const std::string tag = fmt::format("{}{}", part, n);
      fs::create_directories(fs::path(o.out) / "scenarios");
      const std::string scenario = (fs::path(o.out) / "scenarios" / (tag + ".yaml")).string();
      write_scenario_variant(o.scenario, {"parts", part, "mesh", "divisions"}, std::to_string(n),
                             scenario);
      const double ratio = step_ratio(io::read_scenario(scenario));
      std::printf("\nsweep: %s = %d divisions: step ratio %.2f\n", part.c_str(), n, ratio);
      run_mode(scenario, "mono", "mono_" + tag, "mono_" + tag, ratio);
      run_mode(scenario, "multi", "multi_" + tag, "mono_" + tag, ratio);
    }
  }

  auto reference_of = [&](const Row& r) -> const Row& {
    for (const auto& x : rows)
      if (x.name == r.reference) return x;
    return rows.front();
  };
  auto err = [](double x, double r) { return r != 0.0 ? 100.0 * (x - r) / r : 0.0; };
  const fs::path csv = fs::path(o.out) / "sweep.csv";
  std::ofstream f(csv);
  f << "configuration,cpu_s,cpu_over_mono,wall_s,hic15,hic15_error_pct,peak_g,peak_error_pct,"
       "disp_max_m,disp_error_pct,added_mass_kg,step_ratio,reference,note\n";
  std::printf("\n%-20s %9s %9s %9s %10s %8s %9s %8s %10s %8s\n", "config", "CPU [s]", "CPU/mono",
              "wall [s]", "HIC15", "err %", "peak [g]", "err %", "disp [mm]", "err %");
  for (auto& r : rows) {
    for (char& ch : r.note)  // one quoted CSV cell
      if (ch == '"' || ch == '\n') ch = '\'';
    if (!r.ok) {
      f << fmt::format("{},,,,,,,,,,,{:.4f},{},\"{}\"\n", r.name, r.step_ratio, r.reference,
                       r.note);
      std::printf("%-20s failed: %s\n", r.name.c_str(), r.note.c_str());
      continue;
    }
    const Row& ref = reference_of(r);
    const double ratio = ref.ok && ref.cpu_s > 0.0 ? r.cpu_s / ref.cpu_s : 0.0;
    f << fmt::format(
        "{},{:.4f},{:.4f},{:.4f},{:.2f},{:.4f},{:.3f},{:.4f},{:.6e},{:.4f},{:.4f},{:.4f},{},\"{}"
        "\"\n",
        r.name, r.cpu_s, ratio, r.wall_s, r.hic15, err(r.hic15, ref.hic15), r.peak_g,
        err(r.peak_g, ref.peak_g), r.disp_m, err(r.disp_m, ref.disp_m), r.added_mass_kg,
        r.step_ratio, r.reference, r.note);
    std::printf("%-20s %9.2f %9.3f %9.2f %10.1f %+8.2f %9.1f %+8.2f %10.3f %+8.2f\n",
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
