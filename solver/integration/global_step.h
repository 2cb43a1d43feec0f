#pragma once
// What the solver keeps for the global stable step (Controls::global_stable_step): the
// Lanczos estimate of the assembled mesh's highest frequency and the element steps it was taken
// with. The method and its safety are on Solver::refresh_global_step (solver_global_step.cpp);
// docs/elements.md "Global stable step" has the measurements.
#include <cstdint>
#include <limits>
#include <variant>
#include <vector>

#include "solver/elements/hex8_state.h"
#include "solver/elements/shell_bt.h"
#include "solver/integration/top_eigenvalue.h"

namespace crashlink::integration {

struct GlobalStep {
  /// Safety on 2 / sqrt(theta + residual): the Lanczos value is at or below omega_max^2 and
  /// converged to better than 1 % in every patch of the survey; this keeps the step under the
  /// mesh's own 2 / omega_max with a margin for the drift between refreshes.
  static constexpr double kSafety = 0.95;
  /// Lanczos steps of one run (the basis it keeps: kSteps + 1 vectors of 6 doubles per node).
  static constexpr int kSteps = 8;
  /// Runs of a full estimate, each from the last one's Ritz vector (explicit restarts), the
  /// first from the fixed pseudo-random vector: at t = 0 and every kFullEvery-th refresh.
  static constexpr int kInitialRuns = 8;
  static constexpr int kFullRuns = 4;
  static constexpr std::int64_t kFullEvery = 8;
  static constexpr std::int64_t kRefreshCycles = 200;  ///< cycles between estimates at most
  /// A refresh also comes when the smallest element ratio falls below this fraction of its value
  /// just after the last one (a mesh that deforms fast).
  static constexpr double kRefreshDrop = 0.95;
  /// The probe's step over the least element step: v dt of a unit velocity stays far below
  /// the elements' size, so the kernels' response is K (v dt) to ~1e-9.
  static constexpr double kProbeStep = 1e-6;

  bool on = false;
  TopEigenvalue lanczos;
  using State = std::variant<std::monostate, elements::Hex8State, elements::ShellState>;
  std::vector<State> probe_states;            ///< [parts] zero-stress copies of the histories
  std::vector<std::vector<double>> probe_dt;  ///< [parts][ne] elastic element steps [s]
  std::vector<std::vector<double>> ref_inv;   ///< [parts][ne] 1 / those at the last refresh [1/s]
  std::vector<double> inv_sqrt_mass;          ///< [6n] 1/sqrt(m) (3n), 1/sqrt(I) (3n); 0: held
  std::vector<double> v, w, f, m;             ///< [3n] the probe's rates and forces
  double probe_dt_s = 0.0;                    ///< the probe's step [s]
  /// kSafety * 2 / sqrt(theta + residual) at the last refresh [s].
  double dt_global_s = std::numeric_limits<double>::infinity();
  /// min over elements of (its step now) / (its elastic step at the last refresh) and where.
  double ratio = 1.0;
  std::size_t ratio_part = 0;
  std::int64_t ratio_element = -1;
  double ratio_at_refresh = 1.0;
  std::int64_t refresh_cycle = 0;           ///< cycle of the last refresh
  bool binds = false;                       ///< the global step set dt_stable this cycle
  std::vector<double> chunk_ratio;          ///< [chunks] per chunk, folded in chunk order
  std::vector<std::int64_t> chunk_element;  ///< [chunks] its element
  TopEigenvalue::Estimate last;             ///< of the last refresh
  std::int64_t refreshes = 0, products = 0;
};

}  // namespace crashlink::integration
