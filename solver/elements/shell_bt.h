#pragma once
// Belytschko-Tsay 4-node shell: one in-plane integration point, Gauss points through the thickness,
// corotational local frame, Mindlin kinematics, hourglass control by generalized stiffness forces.
// Element numbering: Part::connectivity holds 4 node indices per element, counter-clockwise about
// the shell normal; a triangle is the degenerate quad with connectivity[4e+3] == connectivity[4e+2]
// (LS-DYNA's N3 = N4 convention, 0-based here), whose membrane response is the exact
// constant-strain triangle. Formulas: shell_bt_forces.cpp; more in docs/elements.md.
//
// Sources:
//   [BLT84] Belytschko, Lin, Tsay 1984, "Explicit algorithms for the nonlinear dynamics of
//           shells", CMAME 42, 225-251 (corotational frame, velocity strains, resultants).
//   [BT83]  Belytschko, Tsay 1983, "A stabilization procedure for the quadrilateral plate element
//           with one-point quadrature", IJNME 19, 405-419 (hourglass control).
//   [FB81]  Flanagan, Belytschko 1981, IJNME 17, 679-706 (hourglass shape vector gamma).
//   [LSTM]  Hallquist, LS-DYNA Theory Manual (2006), chapter 7 "Belytschko-Tsay shell" and chapter
//           "Time step control" (shell characteristic length).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/elements/kernel_io.h"
#include "solver/materials/material.h"
#include "solver/model/model.h"

namespace crashlink::elements {

/// Elements processed together by the kernel (gather -> SoA lanes -> scatter-add).
inline constexpr std::size_t kShellLanes = 8;
static_assert(kElementBatch % kShellLanes == 0, "element ranges must start on a shell batch");
/// Largest supported number of Gauss points through the thickness.
inline constexpr int kShellMaxPoints = 10;
/// Transverse shear correction factor of the Mindlin plate (Reissner's 5/6).
inline constexpr double kShellShearFactor = 5.0 / 6.0;

/// Integration-point and hourglass history of one shell part (ne elements, np = through-thickness
/// points, L = kShellLanes, ns = stride = ne rounded up to L so a batch of lanes may read and write
/// past the last element harmlessly). Every per-element array is blocked by batches of L elements
/// ("AoSoA"): an array of R rows per element is [ns/L][R][L], row r of element e at
/// (e/L * R + r) * L + e % L (block_index), so that a batch reads and writes one contiguous block
/// per array (one memory stream each, whatever np).
/// Two forms, chosen by the first shell_internal_forces call from the material (make_shell_state
/// does not know it and returns the point form with zero stress):
///   point form (J2 plasticity): the in-plane stress at every Gauss point
///     sigma_Pa     R = 3 np, row 3k + c: component c (0 xx, 1 yy, 2 xy) at point k; local
///                               corotational frame [Pa]
///     eps_p        R = np, row k: equivalent plastic strain at point k [-]
///   resultant form (elastic): the stress is linear through the thickness, sigma(zeta) = a + zeta b
///     (every increment C (d + zeta h/2 k) dt is), so two stresses per component hold it exactly:
///     resultant_Pa R = 6, rows a_xx, a_yy, a_xy, b_xx, b_yy, b_xy [Pa]; the resultants are N = h a
///                               and M = h^2 b / 6 (Gauss quadrature with np >= 2 points integrates
///                               the linear profile exactly, so both forms give the same forces,
///                               energies and point stresses)
///     sigma_Pa and eps_p are empty.
///   both forms:
///     shear_Pa     R = 2, rows tau_yz, tau_zx: transverse shear (elastic, so constant through the
///                               thickness: every point receives the same increment kG gamma dt)
///                               [Pa]
///     thickness_m  R = 1: current thickness (updated from the thickness strain) [m]
///     hourglass    R = 5: generalized hourglass forces in the local frame Q_x, Q_y, Q_z [N],
///                               Q_thx, Q_thy [N m]
///   damped parts only (Part::damped(); empty otherwise), stiffness-proportional damping:
///     damping_beta_s    R = 1: beta_e = xi_e L_e / c [s], recorded at the first call
///     damping_stress_Pa R = 8: viscous stresses in the force at t^n (for the trapezoid work; not
///                               part of the material state): membrane a_xx, a_yy, a_xy, bending
///                               b_xx, b_yy, b_xy (sigma_d = a + zeta b), shear tau_yz, tau_zx [Pa]
/// Bytes per element of history: point form 8 (4 np + 8): 224 B for np = 5; resultant form
/// 8 * 14 = 112 B for any np; damping adds 8 * 9 = 72 B.
struct ShellState {
  std::size_t element_count = 0;
  std::size_t stride = 0;            ///< element_count rounded up to kShellLanes
  int points = 0;                    ///< Gauss points through the thickness
  std::vector<double> zeta;          ///< [np] Gauss-Legendre abscissae in [-1, 1]
  std::vector<double> weight;        ///< [np] Gauss-Legendre weights (sum 2)
  std::vector<double> sigma_Pa;      ///< point form: [ns/L][np][3][L]; empty in the resultant form
  std::vector<double> eps_p;         ///< point form: [ns/L][np][L]; empty in the resultant form
  std::vector<double> resultant_Pa;  ///< resultant form: [ns/L][6][L]; empty in the point form
  std::vector<double> shear_Pa;      ///< [ns/L][2][L]
  std::vector<double> thickness_m;   ///< [ns]
  std::vector<double> bulk_q_Pa;     ///< [ns] membrane bulk-viscosity pressure at t^n [Pa]
  std::vector<double> hourglass;     ///< [ns/L][5][L]
  std::vector<double> damping_beta_s;     ///< damped parts: [ns]; else empty
  std::vector<double> damping_stress_Pa;  ///< damped parts: [ns/L][8][L]; else empty
  bool damping_recorded = false;          ///< damping_beta_s filled (first kernel call)

  /// Index of row r of element e in a blocked array of R rows per element (layout above).
  static std::size_t block_index(std::size_t R, std::size_t r, std::size_t e) {
    return (e / kShellLanes * R + r) * kShellLanes + e % kShellLanes;
  }
  /// True once an elastic material has put the history into the resultant form.
  bool resultant_form() const { return !resultant_Pa.empty(); }

  /// Stress component c (0 xx, 1 yy, 2 xy, 3 yz, 4 zx) at Gauss point k of element e, local frame
  /// [Pa], in either form.
  double sigma(int c, int k, std::size_t e) const {
    const auto uc = static_cast<std::size_t>(c), uk = static_cast<std::size_t>(k);
    if (c >= 3) return shear_Pa[block_index(2, uc - 3, e)];
    if (resultant_form())
      return resultant_Pa[block_index(6, uc, e)] +
             zeta[uk] * resultant_Pa[block_index(6, uc + 3, e)];
    return sigma_Pa[block_index(3 * static_cast<std::size_t>(points), 3 * uk + uc, e)];
  }
  /// Hourglass force component c (0..4) of element e.
  double hourglass_force(int c, std::size_t e) const {
    return hourglass[block_index(5, static_cast<std::size_t>(c), e)];
  }
  /// Equivalent plastic strain at Gauss point k of element e (0 in the resultant form).
  double plastic_strain(int k, std::size_t e) const {
    return eps_p.empty() ? 0.0
                         : eps_p[block_index(static_cast<std::size_t>(points),
                                             static_cast<std::size_t>(k), e)];
  }
};

/// Zero history for `part` (Shell4): thickness = part.thickness_m, through_thickness_points Gauss
/// points. Throws ModelError unless 3 <= points <= kShellMaxPoints and thickness > 0.
ShellState make_shell_state(const model::Part& part);

/// Converts st to the resultant form (least-squares projection on a + zeta b with the Gauss
/// weights: exact for stresses linear through the thickness, and it keeps N and M of any profile)
/// or to the point form (eps_p = 0). No-ops when st is in that form already; shell_internal_forces
/// calls them on its first call with a part's material.
void shell_state_to_resultant_form(ShellState& st);
void shell_state_to_point_form(ShellState& st);

/// Gauss-Legendre abscissae and weights on [-1, 1] (n <= kShellMaxPoints).
void gauss_legendre(int n, double* zeta, double* weight);

/// Lumped mass: m_e = rho h A (A from the diagonals of the reference geometry x0 [3n]), a quarter
/// to each node of a quad, a third to each node of a triangle; ADDED into mass [n] [kg].
/// Rotational inertia, ADDED into inertia [n] [kg m^2], per node: I = m_node * max(h^2/12, A/8).
/// h^2/12 is the shell's own rotary inertia; the area term is the Key-Beisinger style rotary
/// mass scaling used by crash codes (LS-DYNA, [LSTM] "mass matrix" of the BT shell; Belytschko,
/// Liu, Moran 2000, section 9.5) so that the transverse-shear/rotation frequencies stay below the
/// membrane ones: the translational step L_e/c (shell_internal_forces) is then stable, which the
/// eigenvalue test in tests/unit/elements/shell_bt_stable_step_test.cpp checks.
void shell_lumped_mass(const model::Part& part, const materials::Material& mat, const double* x0,
                       double* mass, double* inertia);

/// Internal forces and moments of the part at t^{n+1} ADDED into nv.f, nv.m (global frame); stress
/// update over dt^n = step.dt_s (none when 0); stable step and energy increments returned.
/// Throws NumericalError for an element of zero (or non-finite) area, naming it.
/// An elastic material puts st into the resultant form, a J2 material into the point form (the
/// conversion is exact for stresses linear through the thickness; see ShellState).
/// Artificial bulk viscosity (step.bulk_viscosity; the integrator sets it from
/// Controls::shell_bulk_viscosity) acts on the membrane: for an in-plane area rate
/// tr D_m = d_xx + d_yy < 0, q = rho L_e (Q2 L_e tr^2 - Q1 c tr) is an in-plane pressure (formula
/// and sources in shell_bt_forces.cpp).
/// A damped part (Part::damping_ratio) adds the stiffness-proportional viscous stress
/// beta_e C (d + z k) at every point and beta_e kappa G gamma in shear (shell_bt_forces.cpp).
KernelResult shell_internal_forces(const model::Part& part, const materials::Material& mat,
                                   ShellState& st, const NodalView& nv, const StepInfo& step);

/// Per-element output: von Mises and eps_p as the maximum over the thickness points; stress_Pa (if
/// non-null) at the mid-surface (the middle point, or the mean of the two middle points for an
/// even count), in the element's LOCAL corotational frame (xx, yy, zz = 0, xy, yz, zx).
void shell_element_output(const model::Part& part, const ShellState& st, const ElementOutput& out);

}  // namespace crashlink::elements
