#include "solver/materials/plane_stress_update.h"

#include <cmath>
#include <limits>

#include "core/errors.h"

namespace crashlink::materials {

HardeningView HardeningView::from(const HardeningCurve& h) {
  HardeningView v;
  v.eps_p = h.eps_p.data();
  v.sigma_y_Pa = h.sigma_y_Pa.data();
  v.n = h.eps_p.size();
  for (std::size_t i = 1; i < v.n; ++i)
    if (h.sigma_y_Pa[i] < h.sigma_y_Pa[i - 1]) v.non_decreasing = false;
  return v;
}

PlaneStressReturn plane_stress_j2_return(const PlaneStressElastic& c, const HardeningView& h,
                                         double& s_xx, double& s_yy, double& s_xy, double& eps_p) {
  PlaneStressReturn out;
  // Eigen-coordinates of the trial stress (Simo & Hughes 1998, section 3.4.2: C and P share the
  // eigenvectors (1,1,0)/sqrt2, (1,-1,0)/sqrt2, (0,0,1)).
  const double a_tr = 0.5 * (s_xx + s_yy);
  const double b_tr = 0.5 * (s_xx - s_yy);
  const double c_tr = s_xy;
  const double vm_tr = std::sqrt(a_tr * a_tr + 3.0 * (b_tr * b_tr + c_tr * c_tr));
  double sy = 0.0, H = 0.0;
  h.evaluate(eps_p, sy, H);
  if (vm_tr <= sy * (1.0 + kPlaneStressReturnTolerance)) return out;

  // Closed-form stress for a given dgamma (sigma = (C^-1 + dgamma P)^-1 C^-1 sigma_trial):
  //   a = a_tr / (1 + k1 dgamma), k1 = E/(3(1-nu));   b, c = (b_tr, c_tr) / (1 + k2 dgamma), k2 =
  //   2G.
  const double k1 = c.E_Pa / (3.0 * (1.0 - c.nu));
  const double k2 = 2.0 * c.G_Pa;
  const double ep_n = eps_p;
  double g = 0.0;  // dgamma [1/Pa]
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  double a = a_tr, bb = b_tr, cc = c_tr, vm = vm_tr;
  for (int it = 1; it <= 100; ++it) {
    const double f1 = 1.0 / (1.0 + k1 * g);
    const double f2 = 1.0 / (1.0 + k2 * g);
    a = a_tr * f1;
    bb = b_tr * f2;
    cc = c_tr * f2;
    vm = std::sqrt(a * a + 3.0 * (bb * bb + cc * cc));
    const double ebar = ep_n + (2.0 / 3.0) * g * vm;  // d_eps_bar = 2/3 dgamma vm
    h.evaluate(ebar, sy, H);
    const double r = vm - sy;  // consistency condition vm(dgamma) = sigma_y(eps_bar(dgamma))
    out.iterations = it;
    if (std::abs(r) <= kPlaneStressReturnTolerance * sy) break;
    if (r > 0.0)
      lo = g;
    else
      hi = g;
    // d vm / d dgamma from d a / d dgamma = -k1 a f1 (and likewise b, c with k2).
    const double dvm = -(k1 * f1 * a * a + 3.0 * k2 * f2 * (bb * bb + cc * cc)) / vm;
    const double debar = (2.0 / 3.0) * (vm + g * dvm);
    const double dr = dvm - H * debar;
    double g_new = (dr < 0.0) ? g - r / dr : -1.0;
    // Safeguard: keep the iterate inside the bracket [lo, hi], bisect otherwise (and after 30
    // iterations, where Newton may cycle across a kink of the piecewise-linear curve).
    if (!(g_new > lo && g_new < hi) || it > 30) {
      g_new = std::isfinite(hi) ? 0.5 * (lo + hi) : (g > 0.0 ? 4.0 * g : 1.0 / k2);
    }
    g = g_new;
    if (it == 100)
      throw NumericalError(fmt::format(
          "plane-stress J2 return did not converge in 100 iterations: trial von Mises {} Pa, "
          "eps_p {}, residual {} Pa; check the hardening curve (slopes below -E/3 are not "
          "supported)",
          vm_tr, ep_n, r));
  }
  s_xx = a + bb;
  s_yy = a - bb;
  s_xy = cc;
  out.d_eps_p = (2.0 / 3.0) * g * vm;
  eps_p = ep_n + out.d_eps_p;
  // d_eps_p_xx + d_eps_p_yy = dgamma (P sigma)_xx + (P sigma)_yy = dgamma (s_xx + s_yy)/3.
  out.d_eps_zz_p = -g * (2.0 * a) / 3.0;
  return out;
}

}  // namespace crashlink::materials
