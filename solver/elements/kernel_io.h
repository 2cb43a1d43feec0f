#pragma once
// What every element kernel reads and writes: views into the domain's nodal arrays, the step just
// taken, and what the kernel reports back. The integrator (solver/integration) owns the arrays.
//
// Time levels follow [2] of Bourel 2005: the kernel is called after u^{n+1} = u^n + dt^n v^{n+1/2};
// it sees x = x0 + u^{n+1} and the mid-step velocities v^{n+1/2}, updates stresses from t^n to
// t^{n+1} with the rate of deformation D(v^{n+1/2}) at the mid-step configuration, and ADDS the
// internal forces f_int(u^{n+1}) into f (and moments into m for shells).
#include <cstddef>
#include <cstdint>
#include <limits>

namespace crashlink::elements {

/// Views of the nodal arrays, all interleaved xyz, n = node count of the domain.
struct NodalView {
  const double* x = nullptr;      ///< [3n] coordinates at t^{n+1} [m]
  const double* v = nullptr;      ///< [3n] velocities at t^{n+1/2} [m/s]
  const double* omega = nullptr;  ///< [3n] angular velocities at t^{n+1/2} [rad/s] (shells)
  double* f = nullptr;            ///< [3n] internal force accumulator [N]: kernels add f_int
  double* m = nullptr;            ///< [3n] internal moment accumulator [N m] (shells)
  /// Slot accumulators [3 slots] [N], [N m]: where StepInfo::scatter sends a corner's force and
  /// moment instead of its node's (null without a scatter plan).
  double* f_slot = nullptr;
  double* m_slot = nullptr;
};

/// The step just taken and the options that shape the element response.
struct StepInfo {
  double dt_s = 0.0;           ///< dt^n = t^{n+1} - t^n [s]; 0 at the initial call (t = 0)
  bool bulk_viscosity = true;  ///< artificial bulk viscosity on (linear + quadratic)
  double q_linear = 0.06;      ///< Q1 [-]
  double q_quadratic = 1.5;    ///< Q2 [-]
  /// The linear (Q1) term in expansion too, as Abaqus/Explicit's linear bulk viscosity; the
  /// quadratic term stays compression-only. Off: LS-DYNA's convention, q = 0 in expansion.
  bool linear_in_expansion = false;
  /// If set: [ne] each element's stable step written (the value whose minimum is
  /// KernelResult::dt_stable_s; `crashlink advise`). Null in runs.
  double* element_dt_s = nullptr;
  /// The elements [first_element, end_element) of the part (end clamped to the part's count):
  /// a domain computes the elements that do not touch its ghost nodes while it waits for their
  /// motion, and the rest after (Solver::end_cycle_interior_forces). first_element must be a
  /// multiple of kElementBatch (the kernels' blocked histories); the forces and histories of
  /// [0, s) then [s, ne) are those of one call over [0, ne), to the bit. Only after the initial
  /// call (which records the reference state of every element).
  std::size_t first_element = 0;
  std::size_t end_element = std::numeric_limits<std::size_t>::max();
  /// Null: each element adds its forces into its nodes' f (and m). Otherwise [k ne] (k corners
  /// per element, element-major as the connectivity): corner c of element e adds into node
  /// scatter[k e + c] when that is >= 0, into slot -1 - scatter[k e + c] of NodalView::f_slot
  /// (m_slot) when < 0: threads that compute disjoint element ranges at once then never add
  /// into the same value (integration::ElementChunks, docs/threads.md).
  const std::int32_t* scatter = nullptr;
  /// Deferred J2 returns (the rim of an lts fine domain, Solver::set_rim_returns; docs/
  /// multirate.md "Plasticity on the rim"). The material history of these elements then advances
  /// only at the calls that do not defer: over a coarse step its plastic state is that of one
  /// return from the start of the step (a coarse element's update), and between those calls the
  /// stress is a function of the strain alone (the return from a fixed plastic strain, an
  /// incremental potential), which no back-and-forth of the path can ratchet.
  /// trial_history: the stresses held are elastic trials from the plastic strain held (the
  /// elements' last call deferred); the stress at t^n, for the work of the step, is their return.
  bool trial_history = false;
  /// defer_return: hold the elastic trial at t^{n+1} and leave the plastic strain (and a shell's
  /// thickness) as it is; the forces and the work use the trial's return.
  bool defer_return = false;
};

/// The force accumulator of corner target t of a scatter plan (StepInfo::scatter): node t's
/// xyz in f when t >= 0, slot -1 - t's in f_slot otherwise.
inline double* scatter_target(double* f, double* f_slot, std::int32_t t) {
  return t >= 0 ? f + 3 * static_cast<std::size_t>(t)
                : f_slot + 3 * static_cast<std::size_t>(-1 - t);
}

/// Element ranges (StepInfo::first_element) start at multiples of this: the shell kernel's lane
/// count and a multiple of the hexahedron kernel's (static_asserts in shell_bt.h and hex8.cpp).
inline constexpr std::size_t kElementBatch = 8;

/// What a kernel call reports. Energies are increments over [t^n, t^{n+1}] by the midpoint rule.
struct KernelResult {
  double dt_stable_s =
      std::numeric_limits<double>::infinity();  ///< min over the part, no safety factor
  std::int64_t critical_element = -1;           ///< local index of the element giving dt_stable_s
  double internal_energy_increment_J = 0.0;     ///< stress work incl. bulk viscosity
  double hourglass_energy_increment_J = 0.0;    ///< work of the hourglass forces
  /// Work of the stiffness-proportional damping stress (Part::damping_ratio), already included
  /// in internal_energy_increment_J; 0 for undamped parts.
  double damping_energy_increment_J = 0.0;
};

/// Per-element output for field states and summaries.
struct ElementOutput {
  double* von_mises_Pa = nullptr;  ///< [ne] von Mises stress (max over integration points)
  double* eps_p = nullptr;         ///< [ne] effective plastic strain (max over integration points)
  double* stress_Pa = nullptr;  ///< [6*ne] Voigt xx,yy,zz,xy,yz,zx, global frame, element e at 6e
                                ///< (shells: mid-surface point); may be null
};

}  // namespace crashlink::elements
