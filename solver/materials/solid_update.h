#pragma once
// Three-dimensional (solid) material updates at one integration point: hypoelastic increment and
// J2 radial return with isotropic piecewise-linear hardening. SI units. Sources: Belytschko-Liu-
// Moran 2014, "Nonlinear Finite Elements for Continua and Structures" (BLM); Simo & Hughes 1998,
// "Computational Inelasticity". Formulas on the functions.
//
// Components: symmetric tensors in Voigt order xx, yy, zz, xy, yz, zx. Stresses are Cauchy
// stresses [Pa]; rates of deformation D are TENSOR components (D_xy, not the engineering shear
// 2 D_xy) [1/s].
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "solver/materials/material.h"

namespace crashlink::materials {

/// Symmetric tensor in Voigt order xx, yy, zz, xy, yz, zx (tensor components).
using Voigt6 = std::array<double, 6>;

/// von Mises equivalent stress sqrt(3/2 s:s) of a Cauchy stress [Pa].
inline double von_mises(const Voigt6& sigma) {
  const double p = (sigma[0] + sigma[1] + sigma[2]) / 3.0;
  const double sx = sigma[0] - p, sy = sigma[1] - p, sz = sigma[2] - p;
  const double ss = sx * sx + sy * sy + sz * sz +
                    2.0 * (sigma[3] * sigma[3] + sigma[4] * sigma[4] + sigma[5] * sigma[5]);
  return std::sqrt(1.5 * ss);
}

/// Hypoelastic increment sigma += dt (lambda tr(D) I + 2 mu D) of the isotropic law
/// sigma_dot = lambda tr(D) I + 2 mu D (BLM eq. 5.4.1 with the Jaumann rate, Box 5.1). The
/// objective (rotation) part is applied by the element before this call.
/// lambda_Pa, mu_Pa: Lame constants; d: rate of deformation [1/s]; dt_s: step [s].
inline void hypoelastic_increment(double lambda_Pa, double mu_Pa, const Voigt6& d, double dt_s,
                                  Voigt6& sigma) {
  const double ltr = lambda_Pa * (d[0] + d[1] + d[2]);
  const double two_mu = 2.0 * mu_Pa;
  sigma[0] += dt_s * (ltr + two_mu * d[0]);
  sigma[1] += dt_s * (ltr + two_mu * d[1]);
  sigma[2] += dt_s * (ltr + two_mu * d[2]);
  sigma[3] += dt_s * two_mu * d[3];
  sigma[4] += dt_s * two_mu * d[4];
  sigma[5] += dt_s * two_mu * d[5];
}

/// Result of a J2 return.
struct J2Return {
  double delta_eps_p = 0.0;  ///< effective plastic strain increment [-] (0: elastic step)
  double yield_Pa = 0.0;     ///< sigma_y(ep_n + delta_eps_p) [Pa]
};

/// The segment of the hardening curve on which a return from eps_p_n starts: yield stress
/// sigma_y(eps_p_n) [Pa], slope H [Pa] of the segment [eps_p_n, end) (right-hand slope at a kink)
/// and its end (infinity on the last, extrapolated segment). If the return ends on this segment,
/// it is the closed form d_ep = (q_tr - yield) / (3 mu + H) of j2_radial_return: batched
/// kernels evaluate that lane-wise and call j2_radial_return only for the rest.
struct J2Segment {
  double yield_Pa = 0.0;  ///< sigma_y(eps_p_n) [Pa]
  double slope_Pa = 0.0;  ///< H on [eps_p_n, end) [Pa]
  double end = 0.0;       ///< effective plastic strain where the segment ends [-]
};
inline J2Segment j2_segment(const HardeningCurve& h, double eps_p_n) {
  const std::size_t n = h.eps_p.size();
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (n == 1) return {h.sigma_y_Pa[0], 0.0, inf};
  auto slope = [&](std::size_t i) {
    return (h.sigma_y_Pa[i] - h.sigma_y_Pa[i - 1]) / (h.eps_p[i] - h.eps_p[i - 1]);
  };
  std::size_t i = 1;  // segment [eps_p[i-1], eps_p[i]) holding eps_p_n (the last one is open)
  while (i + 1 < n && eps_p_n >= h.eps_p[i]) ++i;
  // HardeningCurve::yield takes the segment on the left of a kink: same value, same arithmetic
  const std::size_t iy = (i > 1 && eps_p_n == h.eps_p[i - 1]) ? i - 1 : i;
  const double yield = h.sigma_y_Pa[iy - 1] + slope(iy) * (eps_p_n - h.eps_p[iy - 1]);
  // the end as in the segment walk of j2_radial_return (its first step)
  return {yield, slope(i), eps_p_n < h.eps_p[i] ? h.eps_p[i] : inf};
}

/// Lower bound of sigma_y over all eps_p >= 0 [Pa] (0 if the curve ends with a softening slope):
/// a trial stress with q_tr <= this bound is elastic without a look-up of the curve.
double j2_yield_lower_bound(const HardeningCurve& h);

/// J2 radial return (Simo & Hughes 1998, Box 3.1; BLM Box 5.5) of a trial stress (in: trial
/// Cauchy stress, out: returned stress) with isotropic piecewise-linear hardening h scaled by
/// `scale` (the Cowper-Symonds factor of the step, cowper_symonds.h; 1: none), shear modulus
/// mu_Pa, effective plastic strain eps_p_n at t^n. With the trial deviator s_tr,
/// q_tr = sqrt(3/2 s_tr:s_tr), the backward-Euler consistency condition for the effective plastic
/// strain increment d_ep is
///   q_tr - 3 mu d_ep - sigma_y(ep_n + d_ep) = 0,            s = (1 - 3 mu d_ep / q_tr) s_tr.
/// On one linear segment of the curve (slope H) d_ep = (q_tr - 3 mu d_acc - sigma_y(ep)) / (3 mu +
/// H) in closed form; the solver walks the segments, so the return is exact on the
/// piecewise-linear curve (no Newton tolerance). Throws NumericalError if a softening segment is
/// steeper than -3 mu (the return has no unique solution there).
J2Return j2_radial_return(const HardeningCurve& h, double mu_Pa, double eps_p_n, Voigt6& sigma,
                          double scale = 1.0);

}  // namespace crashlink::materials
