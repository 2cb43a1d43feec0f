#pragma once
// Coulomb friction with an elastic predictor and a return to the cone (Hallquist, LS-DYNA
// Theory Manual, "Friction"), with an exponential decay of mu with the slip speed; the formulas
// are on friction_update and FrictionLaw::mu. Vectors are [3]; all in the global frame.
#include <cmath>

namespace crashlink::contact {

struct FrictionLaw {
  double mu_static = 0.0;
  double mu_dynamic = 0.0;
  double decay_s_m = 0.0;
  bool active() const { return mu_static > 0.0 || mu_dynamic > 0.0; }
  /// mu = mu_d + (mu_s - mu_d) exp(-c |v_rel|), c = decay_s_m [s/m], |v_rel| the slip speed
  /// [m/s] (Hallquist, LS-DYNA Theory Manual, "Friction").
  double mu(double v_slip_m_s) const {
    return mu_dynamic + (mu_static - mu_dynamic) * std::exp(-decay_s_m * v_slip_m_s);
  }
};

/// Updates the tangential force on the slave node `ft` [N] in place (Hallquist, LS-DYNA Theory
/// Manual, "Friction"):
///   F* = F^n - k du_t,  du_t = v_t dt (the tangential part of v_rel),
///   F^{n+1} = F* if |F*| <= mu F_n, else mu F_n F* / |F*|   (return to the cone).
/// `n` unit contact normal (pointing to the slave); `v_rel` [m/s] slave minus master velocity at
/// the contact point; `k` stick stiffness [N/m]; `dt` [s]; `fn` normal force magnitude F_n [N].
/// The old force is first rotated onto the current tangent plane (projection, then rescaled
/// to its old magnitude) so that a history carried across a curved surface keeps its size.
inline void friction_update(const FrictionLaw& law, const double* n, const double* v_rel, double k,
                            double dt, double fn, double* ft) {
  const double ftn = ft[0] * n[0] + ft[1] * n[1] + ft[2] * n[2];
  const double old2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
  for (int d = 0; d < 3; ++d) ft[d] -= ftn * n[d];
  const double new2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
  if (new2 > 0.0) {
    const double s = std::sqrt(old2 / new2);
    for (int d = 0; d < 3; ++d) ft[d] *= s;
  }
  const double vn = v_rel[0] * n[0] + v_rel[1] * n[1] + v_rel[2] * n[2];
  double vt[3];
  for (int d = 0; d < 3; ++d) vt[d] = v_rel[d] - vn * n[d];
  const double vslip = std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
  for (int d = 0; d < 3; ++d) ft[d] -= k * dt * vt[d];  // elastic predictor
  const double fmax = law.mu(vslip) * fn;
  const double f = std::sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
  if (f > fmax) {
    const double s = f > 0.0 ? fmax / f : 0.0;  // return to the cone
    for (int d = 0; d < 3; ++d) ft[d] *= s;
  }
}

}  // namespace crashlink::contact
