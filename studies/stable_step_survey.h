#pragma once
// How close an element's stable-step estimate comes to the step the mesh really allows: a patch
// of n x n quads (Belytschko-Tsay shells) or n x n x n hexahedra at a given aspect ratio and
// distortion, free or with its boundary nodes held, and per patch the kernel's own estimate
// against 2/omega_max of the patch, where omega_max^2 is the largest eigenvalue of M^-1 K (K
// assembled column by column from the force kernels themselves, M lumped as in a run). Beside
// them two other element-local estimates: each element's own 2/omega_max,e (the element alone,
// its own lumped mass: a lower bound of the patch's step by Irons' theorem, omega_max <=
// max_e omega_max,e) and LS-DYNA's default lengths. Used by bench_stable_step
// (docs/elements.md "Stable step survey").
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace crashlink::studies {

enum class PatchKind { Quad, Hex };

struct PatchShape {
  PatchKind kind = PatchKind::Quad;
  int n = 5;                    ///< elements per edge
  double size_m = 5e-3;         ///< element edge along y (and z) [m]
  double aspect = 1.0;          ///< edge along x over edge along y (>= 1)
  double distort = 0.0;         ///< interior nodes moved by up to this fraction of the smaller edge
  bool clamped = false;         ///< every dof of the boundary nodes held
  double thickness_m = 1.5e-3;  ///< quads
};

/// Iteration counts at which the power iteration's estimate is recorded (PatchSteps::power_ratio).
constexpr std::size_t kPowerEstimates = 4;
constexpr std::array<int, kPowerEstimates> kPowerIterations{5, 10, 30, 100};

struct PatchSteps {
  int elements = 0;
  double dt_kernel_s = 0.0;   ///< min over elements of the kernel's estimate (KernelResult)
  double dt_patch_s = 0.0;    ///< 2 / omega_max of the patch
  double dt_element_s = 0.0;  ///< min over elements of the element's own 2 / omega_max,e
  /// LS-DYNA's default: shells L = A / longest side, c = sqrt(E / (rho (1 - nu^2)));
  /// solids L = V / largest face area, c = sqrt((lambda + 2 mu) / rho). dt = L / c, min over
  /// elements.
  double dt_lsdyna_s = 0.0;
  /// A global estimate: 2 / sqrt(Rayleigh quotient) after kPowerIterations[i] iterations of the
  /// power method on M^-1/2 K M^-1/2, over dt_patch_s (>= 1 always, falling towards 1).
  std::array<double, kPowerEstimates> power_ratio{};
  /// The solver's stable step with Controls::global_stable_step (Lanczos on M^-1 K, kSafety
  /// included: integration/global_step.h) [s].
  double dt_global_s = 0.0;
};

/// Steel (7850 kg/m^3, 210 GPa, nu 0.3), elastic, bulk viscosity off (a damping, not part of K),
/// default hourglass control. Throws ModelError for a shape out of range (n < 1, aspect < 1,
/// distort outside [0, 0.4]).
PatchSteps survey_patch(const PatchShape& shape);

/// Free vibration of the patch (dt_scale 1.0 by default) with the global stable step: every free
/// node set moving at a pseudo-random velocity of about 1 mm/s (all modes excited, the strains
/// ~1e-7: linear), bulk viscosity off, no damping; the energies sampled every cycle.
struct PatchVibration {
  std::int64_t cycles = 0;
  double dt_first_s = 0.0;  ///< the first step
  double e0_J = 0.0;        ///< total energy (kinetic + internal + hourglass) after cycle 1
  double e_max_J = 0.0;     ///< its largest value over the run
  double e_end_J = 0.0;     ///< at the end
  std::string error;        ///< non-empty: the run stopped (the solver's message)
};
/// dt_scale may exceed 1 here (a step above the estimate, to show what instability looks like).
PatchVibration vibrate_patch(const PatchShape& shape, std::int64_t cycles, double dt_scale = 1.0);

/// "quad 5x5 aspect 2 distort 0.2 free" and the like.
std::string describe(const PatchShape& shape);

}  // namespace crashlink::studies
