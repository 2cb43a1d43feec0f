#pragma once
// Per-element history of a part of one-point hexahedra (Hex8), structure of arrays.
//
// Layouts (ne = element count, e = local element index, SI units):
//   bulk_q_Pa       [ne]     bulk-viscosity pressure applied in the force at t^n [Pa]
//   stress          [6*ne]   Cauchy stress, component c (Voigt xx,yy,zz,xy,yz,zx) at c*ne+e,
//                            global frame [Pa]
//   eps_p           [ne]     effective plastic strain [-] (0 for elastic parts)
//   hourglass_force [12*ne]  Flanagan-Belytschko generalised hourglass forces Q_i,alpha
//                            (alpha = 0..3 mode, i = 0..2 direction) at (3*alpha+i)*ne+e [N]
//   volume0         [ne]     reference volume [m^3], recorded at the first kernel call (t = 0)
//                            and used for the element mass rho*V0 in the stable step
// Only for a damped part (Part::damped(), stiffness-proportional damping, hex8.h); empty otherwise:
//   damping_beta_s    [ne]   beta_e = xi_e (2 / omega_max) [s], recorded at the first kernel call
//   damping_stress_Pa [6*ne] viscous stress beta_e C : D in the force at t^n, component c at
//                            c*ne+e (for the trapezoid work; not part of the material state) [Pa]
#include <cstddef>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::elements {

struct Hex8State {
  std::size_t element_count = 0;
  std::vector<double> stress;
  std::vector<double> eps_p;
  std::vector<double> hourglass_force;
  std::vector<double> volume0;
  std::vector<double> bulk_q_Pa;          ///< [ne] bulk-viscosity pressure in the force at t^n [Pa]
  std::vector<double> damping_beta_s;     ///< [ne] damped parts only, else empty
  std::vector<double> damping_stress_Pa;  ///< [6*ne] damped parts only, else empty
  bool reference_recorded = false;  ///< volume0 filled (by the first hex8_internal_forces call)

  /// Bytes of history per element (for the performance report); a damped part adds
  /// damping_bytes_per_element().
  static constexpr std::size_t bytes_per_element() { return (6 + 1 + 12 + 1 + 1) * sizeof(double); }
  static constexpr std::size_t damping_bytes_per_element() { return (1 + 6) * sizeof(double); }
};

/// Zero stress, zero plastic strain, zero hourglass forces for every element of the part; the
/// damping arrays when part.damped().
Hex8State make_hex8_state(const model::Part& part);

}  // namespace crashlink::elements
