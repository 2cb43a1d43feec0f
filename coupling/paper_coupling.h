#pragma once
// The coordinator's side of the `paper` coupling scheme (docs/design.md §2.2-§2.4; Bourel,
// Combescure, Di Valentin 2005, equations [5]-[11]; the study's scheme S1 in
// coupling-study/mts.py), as pure functions: no transport, no solver, no state.
// By equation: [5] summed_mass; [6]-[8] link_acceleration; [9], [10] interpolation_weight,
// multiscale_acceleration; [11] drift_step_product, drift_correction, drift_stiffness.
//
// Array shapes (n = interface node count; vectors are xyz interleaved):
//   masses                 [n]        kg
//   accelerations          [3n]       m/s^2
//   displacements          [3n]       m
//   partial masses         [domains][n]
//   free accelerations     [domains][3n]
// Sizes are checked (crashlink::ModelError with the sizes); no function allocates except
// summed_mass. Inputs are never modified; an output may not alias an input.
#include <span>
#include <vector>

#include "coupling/schedule.h"
#include "coupling/ticks.h"

namespace crashlink::coupling::paper {

/// [5], §2.2 of docs/design.md: M[i] = sum_k partial[k][i], summed in domain order (k = 0, 1, ...),
/// so every domain receives the same bits. partial: [domains][n] kg (a copy of another domain's
/// slave node contributes 0: it has no own mass). Each domain then computes its free acceleration
/// a^k = f^k / M ([5]). Throws ModelError for no domain, unequal lengths, a negative or non-finite
/// mass, or a node whose sum is not positive.
std::vector<double> summed_mass(std::span<const std::vector<double>> partial);

/// [8] (with the link problem [6] and [7]): the corrected (link) acceleration of the nodes shared
/// by several domains at a common instant,
/// out[i] = sum_k a_free[k][i], in domain order. a_free: [domains][3n]; out: [3n]. Every domain
/// sharing the node receives this same vector ([8]: U*_A = U*_B = U_A + U_B).
void link_acceleration(std::span<const std::span<const double>> a_free, std::span<double> out);

/// [10]'s weight of instant t between the partner's free states at t0 <= t <= t1 (ticks):
/// theta = (t - t0) / (t1 - t0) as an exact fraction; t0 == t1 == t gives 0/1 (the state itself).
/// Throws ModelError when t is outside [t0, t1] or t1 < t0 (the partner has no bracketing states:
/// a scheduling error).
Weight interpolation_weight(Tick t, Tick t0, Tick t1);

/// [9] with [10]: domain A's corrected acceleration at its instant t_A inside the partner B's step
/// [t_B^n, t_B^{n+1}]:
///   out = a_own + a_B(t_B^n) (1 - theta) + a_B(t_B^{n+1}) theta,   theta = w (see above).
/// (the partner's free acceleration interpolated linearly between its two free states
/// t_B^n <= t_A <= t_B^{n+1}, [10], and added to A's own, [9]). All [3n]. At theta = 0 or 1 this
/// is link_acceleration of the two, bit for bit (a + b): coinciding instants give [8] (no
/// interpolation, §2.3).
void multiscale_acceleration(std::span<const double> a_own, std::span<const double> a_partner_lower,
                             std::span<const double> a_partner_upper, Weight w,
                             std::span<double> out);

/// [11] on or off (the stability study switches it off; docs/design.md §2.4).
enum class Drift : bool { off = false, on = true };

/// dt^n dt^{n-1/2} of [11] for the step dt^n about to be taken after the step dt^{n-1}
/// (dt^{n-1/2} = (dt^{n-1} + dt^n) / 2, [2]; dt^{n-1} = 0 at the first cycle, so the product is
/// dt^0 dt^0 / 2 there, as the half-step start of [2]). Throws ModelError unless dt^n > 0 and
/// dt^{n-1} >= 0.
double drift_step_product(double dt_n, double dt_prev);

/// [11] / §2.4: the drift correction, on the NON-reference side only,
///   da[i] = (u_ref[i] - u[i]) / (dt^n dt^{n-1/2})   (Drift::on),   da[i] = 0   (Drift::off).
/// u_ref is the reference side's displacement at the same instant (interpolated by [10] when the
/// instants differ, docs/design.md §2.4); step_product = drift_step_product(...). It moves the node
/// onto u_ref(t) in one step if nothing else acts: a one-sided spring of stiffness
/// M / (dt^n dt^{n-1/2}) (drift_stiffness). All [3n].
void drift_correction(std::span<const double> u_ref, std::span<const double> u, double step_product,
                      Drift drift, std::span<double> da);

/// The stiffness of the one-sided spring [11] puts on a node of summed mass M [kg]:
/// K = M / (dt^n dt^{n-1/2}) [N/m] (its discrete period is exactly 6 steps at a constant step,
/// coupling-study/README.md finding 2).
inline double drift_stiffness(double mass_kg, double step_product) {
  return mass_kg / step_product;
}

/// The corrected acceleration sent back to the non-reference side, [9] + [11]:
///   out = a_link + da,
/// a_link from link_acceleration or multiscale_acceleration, da from drift_correction. All [3n].
void add_drift(std::span<const double> a_link, std::span<const double> da, std::span<double> out);

}  // namespace crashlink::coupling::paper
