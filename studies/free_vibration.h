#pragma once
// The coupling study's long-run stability set-up (../shared/coupling-study, "stability": 1e5
// fine-step free vibration) in 3-D, for the `layer` scheme: a two-part bar (a row of hexes), shell
// plate cut along a line, or hex block; the fine part nf elements of dx = 10 mm along x, the
// coarse part elements r dx long (and wide) after it, so that the stable steps are r apart; both
// ends fixed; a velocity band over [0.3, 0.5] of the fine part plus 1e-4 relative noise on every
// node; bulk viscosity on (the shells' membrane too). Domains "fine" and "coarse".
// Used by tests/integration/layer_stability_test.cpp (issue #4) and `crashlink stability-map`
// (issue #5), which also runs it under the `paper` scheme (run_paper_free_vibration).
//
// Measures, summed energy E = sum of the domains' total_J at every base instant (all domains
// there; it includes what bulk viscosity and damping dissipated, so a rise is net work of the
// coupling):
//   rise       max over the run of (E - running min) / E0 (the criterion as written);
//   late_rise  the same with the running minimum restarted after the first 20 % of the run.
#include <cstdint>
#include <functional>
#include <string>

#include "coupling/coupling_config.h"
#include "solver/cosim/layer_network.h"
#include "solver/model/model.h"

namespace crashlink::studies {

enum class FreeVibrationShape { Bar, Plate, Block };

const char* shape_name(FreeVibrationShape s);  ///< "bar", "shell plate", "hex block"
const char* shape_key(FreeVibrationShape s);   ///< "bar", "plate", "block"

struct FreeVibrationConfig {
  model::InterfaceDamping damping{0.06, 3};
  int fine_elements = 20;
  bool shell_bulk_viscosity = true;
  double bulk_q_linear = 0.06;            ///< Controls::bulk_q_linear, Q1 [-]
  bool bulk_linear_in_expansion = false;  ///< Controls::bulk_linear_in_expansion
  /// Bar and block: every node held in y and z, no lateral velocity: the study's 1-D bar in 3-D
  /// (a row of hexes in uniaxial strain, wave speed sqrt((lambda + 2 mu) / rho)).
  bool uniaxial = false;
};

/// The model for a step ratio r >= 1 (the coarse elements r times the fine ones).
model::Model free_vibration_model(FreeVibrationShape s, double r, const FreeVibrationConfig& cfg);

struct FreeVibrationResult {
  double rise = 0.0;
  double late_rise = 0.0;
  double t_rise_s = 0.0;  ///< when `rise` was reached
  double e0_J = 0.0, e_end_J = 0.0;
  double ratio = 0.0;  ///< the planned (nested) step ratio
  double simulated_s = 0.0;
  std::int64_t fine_steps_run = 0;  ///< fine steps done (before the stop, if stopped)
  std::string error;                ///< non-empty: the run was stopped (the solver's message)
};

/// One sample of the summed energy: t [s], E/E0 - 1, (E - running min)/E0, hourglass/E0 and the
/// domains' coupling work / E0 (for history prints).
using FreeVibrationSample =
    std::function<void(double, double, double, double, const std::vector<double>&)>;

/// The network options of these studies for a two-domain model ("fine", "coarse") at ratio r:
/// the fine proposal `fine_factor` of mono's stable step, the coarse one r times it, step safety
/// `step_safety`; `scheme` "layer" or "lts" (with `overlap_layers`).
cosim::LayerNetworkOptions free_vibration_options(const model::Model& m, double r,
                                                  const std::string& scheme = "layer",
                                                  double fine_factor = 0.8,
                                                  double step_safety = 0.9,
                                                  int overlap_layers = coupling::kLtsOverlapLayers);

/// Runs `layer` multi for `fine_steps` fine steps (the fine proposal 0.8 of mono's step, the
/// coarse one r times it, step safety 0.9). A crashlink::Error stopping the run is returned in
/// `error` (the measures so far kept).
FreeVibrationResult run_layer_free_vibration(FreeVibrationShape s, double r,
                                             std::int64_t fine_steps,
                                             const FreeVibrationConfig& cfg,
                                             const FreeVibrationSample& on_sample = {});

/// The loop behind run_layer_free_vibration for any two-domain model with domains "fine" and
/// "coarse" (the contact drop of contact_drop.h too).
FreeVibrationResult run_layer_energy(const model::Model& m, double r, std::int64_t fine_steps,
                                     const FreeVibrationSample& on_sample = {});

/// The same under `lts` (leapfrog local time stepping, docs/multirate.md "lts"): the same steps,
/// no interface damping (cfg.damping ignored), the summed energy E measured as for `layer` (the
/// physical one, not lts's conserved E).
FreeVibrationResult run_lts_free_vibration(FreeVibrationShape s, double r, std::int64_t fine_steps,
                                           const FreeVibrationConfig& cfg);

/// The same free vibration under the `paper` scheme (PaperRunner: two domains, no interface
/// damping, H/h = r rounded down to a whole number, h under 0.9 of both stable steps), drift
/// correction [11] on or off. Energy sampled at every coarse instant (PaperRunner::energy). The
/// runner's guard (coupled energy 5 % of its peak above its running minimum, or not finite) stops
/// a run that goes unstable: its message in `error`; a cut the scheme cannot run (shell links
/// carry rotations) too.
FreeVibrationResult run_paper_free_vibration(FreeVibrationShape s, double r,
                                             std::int64_t fine_steps,
                                             const FreeVibrationConfig& cfg, bool drift);
/// The loop behind run_paper_free_vibration for any two-domain model ("fine", "coarse").
FreeVibrationResult run_paper_energy(const model::Model& m, double r, std::int64_t fine_steps,
                                     bool drift);

}  // namespace crashlink::studies
