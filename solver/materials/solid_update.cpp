#include "solver/materials/solid_update.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"

namespace crashlink::materials {

J2Return j2_radial_return(const HardeningCurve& h, double mu_Pa, double eps_p_n, Voigt6& sigma,
                          double scale) {
  const double p = (sigma[0] + sigma[1] + sigma[2]) / 3.0;
  Voigt6 s{sigma[0] - p, sigma[1] - p, sigma[2] - p, sigma[3], sigma[4], sigma[5]};
  const double ss =
      s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  const double q_tr = std::sqrt(1.5 * ss);  // Simo-Hughes Box 3.1 step 2 (as q = sqrt(3/2)|s|)
  const double y_n = scale * h.yield(eps_p_n);
  if (!(q_tr > y_n)) return {0.0, y_n};  // elastic step (also catches q_tr = NaN: no return)

  // Segment walk: on the segment [ep, end) of slope H the residual
  // r(d) = q_tr - 3 mu (acc + d) - (y(ep) + H d) is linear in d.
  const std::size_t n = h.eps_p.size();
  const double three_mu = 3.0 * mu_Pa;
  double ep = eps_p_n;
  double acc = 0.0;  // plastic strain increment accumulated over the finished segments
  for (;;) {
    std::size_t i = 1;
    while (i + 1 < n && ep >= h.eps_p[i]) ++i;
    const double end =
        (n > 1 && ep < h.eps_p[i]) ? h.eps_p[i] : std::numeric_limits<double>::infinity();
    const double H = scale * h.slope(ep);
    if (!(three_mu + H > 0.0))
      throw NumericalError(fmt::format(
          "J2 return: hardening slope {} Pa at eps_p = {} is steeper than -3 mu = {} Pa; the "
          "return map has no unique solution: flatten the softening part of the curve",
          H, ep, -three_mu));
    const double d = (q_tr - three_mu * acc - scale * h.yield(ep)) / (three_mu + H);
    if (ep + d <= end) {
      acc += d;
      break;
    }
    acc += end - ep;
    ep = end;
  }
  const double f = 1.0 - three_mu * acc / q_tr;  // Simo-Hughes Box 3.1 step 4
  sigma = {p + f * s[0], p + f * s[1], p + f * s[2], f * s[3], f * s[4], f * s[5]};
  return {acc, scale * h.yield(eps_p_n + acc)};
}

double j2_yield_lower_bound(const HardeningCurve& h) {
  const std::size_t n = h.eps_p.size();
  if (n > 1 && h.sigma_y_Pa[n - 1] < h.sigma_y_Pa[n - 2]) return 0.0;  // softens without bound
  double y = h.sigma_y_Pa[0];
  for (double s : h.sigma_y_Pa) y = std::min(y, s);
  return y;
}

}  // namespace crashlink::materials
