#pragma once
// What a run will cost, from the model alone (no solver): the stable step estimated element by
// element, the cycles to the end time, the CPU time and the size of the output. Printed at the
// start of every run (`crashlink run`) and bounded by the scenario reader's plausibility checks
// (docs/scenario-format.md "Plausibility checks"): an end time in ms written as s shows here as
// a run of days that fills the disk.
#include <cstddef>
#include <string>

#include "solver/model/model.h"

namespace crashlink::model {

/// CPU cost of one element for one cycle [s]: the measured 63 ns (shell) and 74 ns (hex) of
/// docs/benchmarks.md, rounded to 70 ns.
inline constexpr double kElementCycleCost_s = 70e-9;

/// Estimated stable step [s]: dt_scale x min over the deformable elements of L_e / c, capped by
/// dt_max; L_e the element's shortest edge h times the kernels' length on a regular element (hex:
/// V sqrt(3 / (2 B:B)) = h / sqrt(3) on a cube; shell: A / max diagonal = h / sqrt(2) on a
/// square), c the material's Courant speed (hex: dilatational sqrt((lambda + 2 mu) / rho); shell:
/// plate sqrt(E / (rho (1 - nu^2)))). The solver's own (solver/elements) also sees distortion
/// and the bulk viscosity: this is an estimate for planning. +inf when no element is deformable.
double estimated_stable_step_s(const Model& m);

struct RunEstimate {
  double dt_s = 0.0;          ///< the step it assumes [s]
  double cycles = 0.0;        ///< end_time / dt
  double cpu_s = 0.0;         ///< cycles x deformable elements x kElementCycleCost_s (mono)
  double output_bytes = 0.0;  ///< history rows + field states, 8 bytes a value
};

/// The run of `m` at the step dt_s [s]: history rows every history_interval (every cycle if 0:
/// 12 glstat values + 9 per probe + 3 per contact), field states every field_interval (first and
/// last if 0: displacement and velocity per node, 8 values per element).
RunEstimate estimate_run(const Model& m, double dt_s);

/// "~1.2e+04 cycles at dt 1.6e-06 s, ~12 s of CPU (70 ns per element-cycle), ~35 MB of output".
std::string describe(const RunEstimate& e);

/// "35 MB", "1.2 GB": a byte count for a message.
std::string byte_size(double bytes);
/// "12 s", "3.4 h", "2.1 days": a duration for a message.
std::string duration(double seconds);

}  // namespace crashlink::model
