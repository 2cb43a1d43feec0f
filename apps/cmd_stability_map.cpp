#include "apps/cmd_stability_map.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "apps/python_script.h"
#include "core/errors.h"
#include "studies/contact_drop.h"
#include "studies/free_vibration.h"

namespace crashlink::apps {

CLI::App* add_stability_map_command(CLI::App& app, StabilityMapOptions& options) {
  auto* cmd = app.add_subcommand(
      "stability-map",
      "long-run energy growth of the layer and paper couplings against the step ratio");
  cmd->add_option("--steps", options.steps, "fine steps per run")
      ->check(CLI::Range(10LL, 100000000LL))
      ->capture_default_str();
  cmd->add_option("--ratios", options.ratios, "step ratios H/h (>= 1)")
      ->check(CLI::Range(1.0, 64.0))
      ->delimiter(',');
  cmd->add_option("--shapes", options.shapes,
                  "bar, plate, block (linked, free vibration), contact (a block dropped on a slab "
                  "across the domains)")
      ->check(CLI::IsMember({"bar", "plate", "block", "contact"}))
      ->delimiter(',');
  cmd->add_option("--penalties", options.penalties, "contact: penalty scale factors")
      ->check(CLI::Range(1e-4, 1e4))
      ->delimiter(',');
  cmd->add_option("--out", options.out, "output folder")->capture_default_str();
  return cmd;
}

int run_stability_map(const StabilityMapOptions& o) {
  namespace fs = std::filesystem;
  fs::create_directories(o.out);
  const fs::path csv = fs::path(o.out) / "stability_map.csv";
  std::ofstream f(csv);
  if (!f) throw InputError(fmt::format("stability-map: cannot write {}", csv.string()));
  f << "shape,configuration,ratio,nested_ratio,fine_steps,max_rise,late_rise,e_end_over_e0,"
       "fine_steps_run,stopped\n";
  struct Configuration {
    std::string name;
    bool paper;
    double damping;                    ///< layer: interface damping ratio over 3 element layers
    bool drift;                        ///< paper: [11] on
    double penalty;                    ///< contact: penalty scale
    bool linear_in_expansion = false;  ///< bulk viscosity's Q1 term in expansion too
    bool uniaxial = false;             ///< bar, block: lateral dofs held (the study's 1-D bar)
    double q_linear = 0.06;            ///< bulk viscosity's Q1
    bool lts = false;                  ///< the lts form instead of layer (no damping)
  };
  const std::vector<Configuration> linked = {
      {"layer", false, 0.0, false, 0.0},
      {"layer + interface damping 0.06 x 3 layers", false, 0.06, false, 0.0},
      {"lts", false, 0.0, false, 0.0, false, false, 0.06, true},
      {"paper + drift correction [11]", true, 0.0, true, 0.0},
      {"paper without drift correction", true, 0.0, false, 0.0},
      // Does a linear viscosity acting in expansion too (the study's, Abaqus's) make `paper`
      // stable at r = 2 as in the study's 1-D bar? (docs/paper-scheme.md "Bulk viscosity")
      {"paper + [11] + uniaxial", true, 0.0, true, 0.0, false, true},
      {"paper + [11] + Q1 in expansion", true, 0.0, true, 0.0, true},
      {"paper + [11] + Q1 in expansion + uniaxial", true, 0.0, true, 0.0, true, true},
      {"paper + [11] + Q1 = 0.5 in expansion", true, 0.0, true, 0.0, true, false, 0.5},
      {"paper + [11] + Q1 = 0.5 in expansion + uniaxial", true, 0.0, true, 0.0, true, true, 0.5}};
  std::vector<Configuration> contact;
  for (const double k : o.penalties) {
    contact.push_back({fmt::format("layer penalty x{:g}", k), false, 0.0, false, k});
    contact.push_back(
        {fmt::format("paper + drift correction [11] penalty x{:g}", k), true, 0.0, true, k});
  }
  for (const auto& shape_key : o.shapes) {
    const bool is_contact = shape_key == "contact";
    const auto shape = shape_key == "bar"     ? studies::FreeVibrationShape::Bar
                       : shape_key == "plate" ? studies::FreeVibrationShape::Plate
                                              : studies::FreeVibrationShape::Block;
    for (const auto& c : is_contact ? contact : linked) {
      // uniaxial strain holds a bar's or block's lateral dofs; the plate has no such variant
      if (c.uniaxial && shape == studies::FreeVibrationShape::Plate && !is_contact) continue;
      for (double r : o.ratios) {
        studies::FreeVibrationConfig cfg;
        cfg.damping = {c.damping, 3};
        cfg.bulk_linear_in_expansion = c.linear_in_expansion;
        cfg.uniaxial = c.uniaxial;
        cfg.bulk_q_linear = c.q_linear;
        const auto res =
            is_contact ? (c.paper ? studies::run_paper_contact_drop(r, c.penalty, o.steps, c.drift)
                                  : studies::run_layer_contact_drop(r, c.penalty, o.steps))
            : c.paper  ? studies::run_paper_free_vibration(shape, r, o.steps, cfg, c.drift)
            : c.lts    ? studies::run_lts_free_vibration(shape, r, o.steps, cfg)
                       : studies::run_layer_free_vibration(shape, r, o.steps, cfg);
        const double e_ratio = res.e0_J > 0.0 ? res.e_end_J / res.e0_J : 0.0;
        std::string why = res.error;  // CSV: one quoted cell
        for (char& ch : why)
          if (ch == '"' || ch == '\n') ch = '\'';
        f << fmt::format("{},{},{},{},{},{:.6e},{:.6e},{:.6f},{},{}\n", shape_key, c.name, r,
                         res.ratio, o.steps, res.rise, res.late_rise, e_ratio, res.fine_steps_run,
                         why.empty() ? "" : "\"" + why + "\"");
        f.flush();
        const std::string tail = res.error.empty()
                                     ? std::string()
                                     : fmt::format("  STOPPED after {} fine steps: {}",
                                                   res.fine_steps_run, res.error.substr(0, 160));
        std::printf(
            "%-6s %-50s r = %-5g (nested %-3g): max rise %.3e of E0, after 20 %% %.3e, "
            "E_end/E0 %.4f%s\n",
            shape_key.c_str(), c.name.c_str(), r, res.ratio, res.rise, res.late_rise, e_ratio,
            tail.c_str());
        std::fflush(stdout);
      }
    }
  }
  f.close();
  std::printf("%s\n", csv.string().c_str());
  return run_python_script("stability_map.py", "CRASHLINK_STABILITY_MAP_SCRIPT",
                           {csv.string(), (fs::path(o.out) / "stability_map.png").string()},
                           "stability-map");
}

}  // namespace crashlink::apps
