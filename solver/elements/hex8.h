#pragma once
// The 8-node one-point hexahedron of Flanagan & Belytschko 1981 (FB, IJNME 17, 679-706): uniform
// strain gradient, orthogonal hourglass control in the stiffness form, artificial bulk viscosity,
// hypoelastic (Jaumann) stress update with elastic or J2 material
// (solver/materials/solid_update.h; BLM: Belytschko, Liu, Moran, there).
//
// Arrays: connectivity and nodal views as in model.h and kernel_io.h; history as in hex8_state.h.
// The formulas are on hex8_internal_forces. The kernel (hex8.cpp) evaluates them one element per
// SIMD lane in the mode form of hex8_modes.h; tests/unit/elements/hex8_reference_test checks it
// against a naive per-node implementation of the formulas, bench/bench_hex8.cpp measures it.
// Derivations and choices: docs/elements.md "Hexahedron".
#include "solver/elements/hex8_state.h"
#include "solver/elements/kernel_io.h"
#include "solver/materials/material.h"
#include "solver/model/model.h"

namespace crashlink::elements {

/// Adds rho * V / 8 of every element to each of its nodes: mass [n] [kg], x0 [3n] [m].
/// Throws NumericalError for an element with non-positive volume.
void hex8_lumped_mass(const model::Part& part, const materials::Material& mat, const double* x0,
                      double* mass);

/// Stress update t^n -> t^{n+1} and internal forces at t^{n+1}, added into nv.f. mat.kind is
/// Elastic or J2Plastic. Throws NumericalError (element user id, part name, volume) if an element's
/// volume at x^{n+1/2} or x^{n+1} is not positive. Time levels (kernel_io.h): x = x^{n+1},
/// v = v^{n+1/2}, dt = dt^n.
///  * Rate of deformation at the MID-STEP configuration x^{n+1/2} = x - dt/2 v (BLM Box 6.1; Hughes
///    & Winget 1980): D = 0 to round-off for a rigid motion, and the Cayley (Hughes-Winget)
///    rotation R = (I - dt/2 W)^{-1} (I + dt/2 W) is then exactly the incremental rigid rotation
///    (docs/elements.md "Hexahedron mid-step configuration").
///  * Stress: sigma^{n+1} = R sigma^n R^T + dt (lambda tr D I + 2 mu D) (Jaumann rate, BLM eq.
///    5.4.1 / Box 5.1), then the J2 return for J2Plastic parts.
///  * Internal force at x^{n+1}: f_iI = b_iI (sigma_ij - q delta_ij) + sum_alpha Q_i,alpha
///    gamma_alpha,I, with b = dV/dx (FB eq. 13: f = V B^T sigma, B = b/V).
///  * Hourglass (FB eq. 22-30, stiffness form, like LS-DYNA IHQ = 4): rates qdot_i,alpha =
///    v_iI gamma_alpha,I; Q^{n+1} = R Q^n + k qdot dt with
///        k = kappa (lambda + 2 mu) (b_iI b_iI) / (8 V),   kappa = Part::hourglass_coefficient,
///    i.e. kappa times FB's bound (8/rho)(lambda+2mu) B_iI B_iI on omega_max^2 (FB eq. 31) scaled
///    to a stiffness: on a cube the hourglass frequency is omega_hg^2 = kappa * 8 c^2 B_iI B_iI.
///    The generalised forces rotate with the material (R Q) so the form stays objective.
///  * Bulk viscosity (LS-DYNA convention, Hallquist, LS-DYNA Theory Manual, "Artificial bulk
///    viscosity"): for eps_v_dot = tr D < 0
///        q = rho L (Q2 L eps_v_dot^2 - Q1 c eps_v_dot),   Q2 = StepInfo::q_quadratic (1.5),
///                                                          Q1 = StepInfo::q_linear (0.06),
///    q = 0 in expansion (with StepInfo::linear_in_expansion, Abaqus/Explicit's linear bulk
///    viscosity, Abaqus Analysis User's Guide 6.3.3: the linear term -rho L Q1 c eps_v_dot in
///    expansion too, and Q1 in the step's xi always); rho = current density, c = dilatational
///    wave speed, and L = sqrt(3 / (2 B_iI B_iI)) (= the edge for a cube; docs/elements.md
///    "Hexahedron bulk viscosity length"). q is added to the pressure in the force only, not
///    stored in sigma; its work -q tr(D) V dt is part of the internal energy increment.
///  * Stable step (no safety factor): with lumped mass m = rho V0 / 8 at every node, the highest
///    frequency of the free element satisfies (derivation in hex8.cpp)
///        omega^2 <= 8 / (rho V0) [ V (max(lambda,0) B_iI B_iI + 2 mu lmax(B B^T))  + k lmax(G) ]
///    with B B^T the 3x3 matrix sum_I B_iI B_jI and G the 4x4 Gram matrix gamma_alpha . gamma_beta
///    (lmax bounded by min(Gershgorin, Frobenius)). Sharp for a cube (the volumetric mode attains
///    it). Bulk viscosity reduces it as dt = (2/omega)(sqrt(1+xi^2) - xi) with xi = Q1 + Q2 L
///    |eps_v_dot| / c (BLM section 6.3, critical step with damping), which is LS-DYNA's
///    dt = L/(Q + sqrt(Q^2 + c^2)) with L = 2c/omega.
///  * Stiffness-proportional (Rayleigh beta) damping, parts with Part::damping_ratio or
///    element_damping_ratio > 0 (LS-DYNA *DAMPING_PART_STIFFNESS; damping matrix C = beta K gives
///    mode k the ratio xi_k = beta omega_k / 2: Chopra, Dynamics of Structures, ch. 11, Rayleigh
///    damping):
///        sigma_d = beta_e (lambda tr D I + 2 mu D),   beta_e = xi_e (2 / omega_max,e),
///    with 2 / omega_max,e the bound above at the first call (t = 0), kept for the run (so the
///    damping stays linear). sigma_d is added to the stress in the force only, never to the
///    material history; the force at t^n used sigma_d^n, so its work is the trapezoid
///    1/2 (sigma_d^n + sigma_d^{n+1}) : D V^{n+1/2} dt (sigma_d^n kept in Hex8State), counted in
///    the internal energy and reported as damping_energy_increment_J. Rigid motion: D = 0, no
///    force. Its ratio at the current highest frequency, beta omega_max / 2, adds to the bulk
///    viscosity's xi in the stable step above (both viscous in the same mode; BLM section 6.3).
///    Undamped parts run a separate instance of the kernel without this code.
///  * Energies: internal = 1/2 (R sigma^n R^T + sigma^{n+1}) : D V^{n+1/2} dt + bulk viscosity
///    work + damping work; hourglass = 1/2 (R Q^n + Q^{n+1}) . qdot dt.
///  * At the initial call (dt = 0) nothing is updated but the viscous pressure q^0 (the force at
///    t^0 carries it; the first step's trapezoid work needs it): forces from the current history,
///    dt_stable.
KernelResult hex8_internal_forces(const model::Part& part, const materials::Material& mat,
                                  Hex8State& st, const NodalView& nv, const StepInfo& step);

/// Von Mises stress, effective plastic strain and stress (element e at 6e) of every element.
void hex8_element_output(const model::Part& part, const Hex8State& st, const ElementOutput& out);

}  // namespace crashlink::elements
