#pragma once
// The model's energy scale: the floor under the guard's reference energy (docs/energy-balance.md,
// "The guard's floor"). A domain that holds almost no energy yet (a part the wave has not
// reached: internal energy 1e-323 J) has a balance that is round-off relative to its own energies
// but nothing relative to the model's; its guard divides by the larger of its own reference and
// kGuardFloorFraction x the whole model's scale, so that it stops creation that matters at the
// model's scale and not the noise of a domain at rest.
#include "solver/model/curve.h"

namespace crashlink::integration {

class Solver;

/// Fraction of the model's energy scale under which a domain's balance error is not judged
/// relative to the domain's own energies. 1e-6: above the round-off of sums over a model
/// (N eps E, 1e-10 E for 10^6 elements), below anything the output resolves (the guard's 5 % of it
/// is 5e-8 of the model's energy); an instability grows by a factor each cycle, so it passes this
/// floor within a few tens of cycles, long before a NaN.
inline constexpr double kGuardFloorFraction = 1e-6;

/// The integral of |f(t)| over [0, t_end] [unit of f x s], exact for the piecewise-linear curve
/// (constant before its first point and after its last, as Curve::at).
double integral_of_magnitude(const model::Curve& c, double t_end_s);

/// The kinetic energy of the whole model pushed by its loads and gravity over the run [J]:
///   E = J^2 / (2 M),   J = sum_(loads, nodes) int_0^T |F(t)| dt + M |g| T
/// with M the mass of the nodes not in a rigid body (held ones too) and of the rigid bodies, T the
/// end time: the least kinetic
/// energy a body of mass M can hold with momentum J, which the loads give it when they push one
/// way on a free model. A scale, not a bound: loads that oppose each other count as adding, and
/// a supported model held for many periods of its lowest mode holds less (for n periods,
/// ~ (2 pi n)^2 / 2 times less: a crash transient is a few).
double pushed_energy_J(const Solver& s);

/// The energy scale of the model `s` holds [J], after s.initialize():
///   E = 1/2 sum_i (m_i |v_i^0|^2 + I_i |omega_i^0|^2)     free nodes (not rigid, not ghosts)
///     + 1/2 sum_b (M_b |v_b^0|^2 + omega_b^0 . J_b omega_b^0)    rigid bodies (R = 1 at t = 0)
///     + 1/2 sum_(prescribed dofs k) m_k max_t |v_k(t)|^2          (I_k for a rotation)
/// the initial kinetic energy plus the kinetic energy each prescribed motion gives its nodes at
/// its peak speed (a lower bound of the energy that drive puts into the model)
///     + pushed_energy_J(s)                                        loads and gravity
double model_energy_scale_J(const Solver& s);

}  // namespace crashlink::integration
