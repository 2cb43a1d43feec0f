#pragma once
// Plane-stress material updates at one integration point of a shell (sigma_zz = 0), in the
// element's corotational frame: elastic (hypoelastic increment) and J2 plasticity with isotropic
// piecewise-linear hardening.
//
// J2 algorithm: the projected return of Simo & Taylor 1986 ("A return mapping algorithm for plane
// stress elastoplasticity", IJNME 22, 649-670; also Simo & Hughes, Computational Inelasticity,
// 1998, section 3.4): the backward-Euler closest-point projection in the plane-stress subspace,
// solved exactly in the eigenbasis that diagonalises both the plane-stress elasticity C and the
// von Mises projector P, with a scalar Newton iteration on the plastic multiplier dgamma. No
// iteration on the thickness strain is needed (unlike the LS-DYNA radial return + secant on
// eps_zz): sigma_zz = 0 holds exactly, the thickness strain increment is a by-product.
//
// Notation (vectors of in-plane components, engineering shear strain gamma_xy = 2 eps_xy):
//   sigma = [s_xx, s_yy, s_xy],   d_eps = [d_eps_xx, d_eps_yy, d_gamma_xy]
//   C     = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]          plane-stress elasticity
//   P     = 1/3 [[2, -1, 0], [-1, 2, 0], [0, 0, 6]]                       sigma^T P sigma = 2/3
//   vm^2 vm^2  = s_xx^2 + s_yy^2 - s_xx s_yy + 3 s_xy^2 = a^2 + 3 (b^2 + c^2) with a = (s_xx +
//   s_yy)/2, b = (s_xx - s_yy)/2, c = s_xy (the eigen-coordinates of C and P).
// Flow rule d_eps_p = dgamma P sigma_{n+1}; equivalent plastic strain (work conjugate to vm):
//   d_eps_bar = (2/3) dgamma vm_{n+1}.
// The transverse shear stresses (tau_yz, tau_zx) stay elastic (as in LS-DYNA's shell plasticity
// for the Belytschko-Tsay element); they enter the von Mises output only.
#include <cmath>
#include <cstddef>

#include "solver/materials/material.h"

namespace crashlink::materials {

/// Plane-stress elastic constants, precomputed once per part.
struct PlaneStressElastic {
  double E_Pa = 0.0;    ///< Young's modulus
  double nu = 0.0;      ///< Poisson's ratio
  double c11_Pa = 0.0;  ///< E/(1-nu^2)
  double c12_Pa = 0.0;  ///< nu E/(1-nu^2)
  double G_Pa = 0.0;    ///< E/(2(1+nu))

  static PlaneStressElastic from(const Material& m) {
    const double E = m.youngs_modulus_Pa;
    const double nu_ = m.poisson_ratio;
    return {E, nu_, E / (1.0 - nu_ * nu_), nu_ * E / (1.0 - nu_ * nu_), E / (2.0 * (1.0 + nu_))};
  }
};

/// Elastic plane-stress increment sigma += C d_eps (components as in the header comment).
inline void plane_stress_elastic_update(const PlaneStressElastic& c, double d_eps_xx,
                                        double d_eps_yy, double d_gamma_xy, double& s_xx,
                                        double& s_yy, double& s_xy) {
  s_xx += c.c11_Pa * d_eps_xx + c.c12_Pa * d_eps_yy;
  s_yy += c.c12_Pa * d_eps_xx + c.c11_Pa * d_eps_yy;
  s_xy += c.G_Pa * d_gamma_xy;
}

/// Elastic thickness strain increment of plane stress: d_eps_zz = -nu/E (d_s_xx + d_s_yy).
inline double plane_stress_elastic_thickness_strain(const PlaneStressElastic& c, double d_s_xx,
                                                    double d_s_yy) {
  return -c.nu / c.E_Pa * (d_s_xx + d_s_yy);
}

/// A piecewise-linear hardening curve as flat arrays (a view of HardeningCurve), evaluated
/// exactly as HardeningCurve::yield / slope (last slope extrapolated, right-hand slope at kinks).
struct HardeningView {
  const double* eps_p = nullptr;
  const double* sigma_y_Pa = nullptr;
  std::size_t n = 0;
  bool non_decreasing = true;  ///< sigma_y never decreases: vm <= sigma_y(0) means elastic

  static HardeningView from(const HardeningCurve& h);
  double initial_yield_Pa() const { return sigma_y_Pa[0]; }

  /// sigma_y(ep) [Pa] and the slope H = d sigma_y / d ep [Pa] in one pass over the segments.
  void evaluate(double ep, double& sigma_y, double& H) const {
    if (n == 1) {
      sigma_y = sigma_y_Pa[0];
      H = 0.0;
      return;
    }
    std::size_t i = 1;
    while (i + 1 < n && ep >= eps_p[i]) ++i;
    H = (sigma_y_Pa[i] - sigma_y_Pa[i - 1]) / (eps_p[i] - eps_p[i - 1]);
    sigma_y = sigma_y_Pa[i - 1] + H * (ep - eps_p[i - 1]);
  }
  double yield(double ep) const {
    double sy = 0.0, H = 0.0;
    evaluate(ep, sy, H);
    return sy;
  }
};

/// What the plane-stress J2 return reports.
struct PlaneStressReturn {
  double d_eps_p = 0.0;     ///< increment of the equivalent plastic strain [-]
  double d_eps_zz_p = 0.0;  ///< plastic thickness strain increment -(d_eps_p_xx + d_eps_p_yy)
  int iterations = 0;       ///< Newton iterations (0: the trial state was elastic)
};

/// Relative tolerance of the consistency condition |vm - sigma_y| <= tol * sigma_y.
inline constexpr double kPlaneStressReturnTolerance = 1e-12;

/// Plane-stress J2 return (Simo & Taylor 1986): on entry s_* is the elastic trial stress
/// sigma_n + C d_eps and eps_p the equivalent plastic strain at t^n; on exit the stress and eps_p
/// at t^{n+1} satisfy vm = sigma_y(eps_p) to kPlaneStressReturnTolerance (or are unchanged when the
/// trial state is inside the yield surface). Throws NumericalError if Newton fails (does not
/// happen for a hardening curve whose slope stays above -E/3).
PlaneStressReturn plane_stress_j2_return(const PlaneStressElastic& c, const HardeningView& h,
                                         double& s_xx, double& s_yy, double& s_xy, double& eps_p);

/// Von Mises stress of a shell point: plane stress plus the transverse shears [Pa].
inline double shell_von_mises(double s_xx, double s_yy, double s_xy, double t_yz, double t_zx) {
  const double q =
      s_xx * s_xx + s_yy * s_yy - s_xx * s_yy + 3.0 * (s_xy * s_xy + t_yz * t_yz + t_zx * t_zx);
  return q > 0.0 ? std::sqrt(q) : 0.0;
}

}  // namespace crashlink::materials
