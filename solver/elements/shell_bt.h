#pragma once
// Belytschko-Tsay 4-node shell: one in-plane integration point, Gauss points through the thickness,
// corotational local frame, Mindlin kinematics, hourglass control by generalized stiffness forces.
//
// Sources:
//   [BLT84] Belytschko, Lin, Tsay 1984, "Explicit algorithms for the nonlinear dynamics of
//           shells", CMAME 42, 225-251 (corotational frame, velocity strains, resultants).
//   [BT83]  Belytschko, Tsay 1983, "A stabilization procedure for the quadrilateral plate element
//           with one-point quadrature", IJNME 19, 405-419 (hourglass control).
//   [FB81]  Flanagan, Belytschko 1981, IJNME 17, 679-706 (hourglass shape vector gamma).
//   [LSTM]  Hallquist, LS-DYNA Theory Manual (2006), chapter 7 "Belytschko-Tsay shell" and chapter
//           "Time step control" (shell characteristic length).
//
// Element numbering: Part::connectivity holds 4 node indices per element, counter-clockwise about
// the shell normal. A triangle is the degenerate quad with connectivity[4e+3] == connectivity[4e+2]
// (LS-DYNA's N3 = N4 convention, 0-based here); its membrane response is then the exact
// constant-strain triangle.
//
// Data layout of ShellState (ne elements, np = through-thickness points, ns = stride = ne rounded
// up to kShellLanes so a batch of lanes may read and write past the last element harmlessly):
//   sigma_Pa       [5][np][ns]  component c (0 xx, 1 yy, 2 xy, 3 yz, 4 zx) at point k of element e
//                               at (c*np + k)*ns + e; local corotational frame [Pa]
//   eps_p          [np][ns]     equivalent plastic strain at point k of element e at k*ns + e [-]
//   thickness_m    [ns]         current thickness (updated from the thickness strain) [m]
//   hourglass      [5][ns]      generalized hourglass forces in the local frame, component c at
//                               c*ns + e: Q_x, Q_y, Q_z [N], Q_thx, Q_thy [N m]
// Bytes per element of history: 8 (6 np + 6): 288 B for np = 5.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/elements/kernel_io.h"
#include "solver/materials/material.h"
#include "solver/model/model.h"

namespace crashlink::elements {

/// Elements processed together by the kernel (gather -> SoA lanes -> scatter-add).
inline constexpr std::size_t kShellLanes = 8;
/// Largest supported number of Gauss points through the thickness.
inline constexpr int kShellMaxPoints = 10;
/// Transverse shear correction factor of the Mindlin plate (Reissner's 5/6).
inline constexpr double kShellShearFactor = 5.0 / 6.0;

/// Integration-point and hourglass history of one shell part (layout in the header comment).
struct ShellState {
  std::size_t element_count = 0;
  std::size_t stride = 0;           ///< element_count rounded up to kShellLanes
  int points = 0;                   ///< Gauss points through the thickness
  std::vector<double> zeta;         ///< [np] Gauss-Legendre abscissae in [-1, 1]
  std::vector<double> weight;       ///< [np] Gauss-Legendre weights (sum 2)
  std::vector<double> sigma_Pa;     ///< [5][np][ns]
  std::vector<double> eps_p;        ///< [np][ns]
  std::vector<double> thickness_m;  ///< [ns]
  std::vector<double> hourglass;    ///< [5][ns]

  double& sigma(int c, int k, std::size_t e) {
    return sigma_Pa[(static_cast<std::size_t>(c * points + k)) * stride + e];
  }
  double sigma(int c, int k, std::size_t e) const {
    return sigma_Pa[(static_cast<std::size_t>(c * points + k)) * stride + e];
  }
};

/// Zero history for `part` (Shell4): thickness = part.thickness_m, through_thickness_points Gauss
/// points. Throws ModelError unless 3 <= points <= kShellMaxPoints and thickness > 0.
ShellState make_shell_state(const model::Part& part);

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
/// Artificial bulk viscosity is not applied to shells (LS-DYNA's default for shells).
KernelResult shell_internal_forces(const model::Part& part, const materials::Material& mat,
                                   ShellState& st, const NodalView& nv, const StepInfo& step);

/// Per-element output: von Mises and eps_p as the maximum over the thickness points; stress_Pa (if
/// non-null) at the mid-surface (the middle point, or the mean of the two middle points for an
/// even count), in the element's LOCAL corotational frame (xx, yy, zz = 0, xy, yz, zx).
void shell_element_output(const model::Part& part, const ShellState& st, const ElementOutput& out);

}  // namespace crashlink::elements
