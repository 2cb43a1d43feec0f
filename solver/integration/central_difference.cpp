#include "solver/integration/central_difference.h"

#include <cmath>

namespace crashlink::integration {

void advance_velocity(double* __restrict v, double* __restrict v_prev, const double* __restrict a,
                      double dt_mid, std::size_t len) {
  for (std::size_t i = 0; i < len; ++i) {
    v_prev[i] = v[i];
    v[i] += dt_mid * a[i];
  }
}

void advance_velocity_into(double* __restrict v_next, const double* __restrict v,
                           const double* __restrict a, double dt_mid, std::size_t len) {
  for (std::size_t i = 0; i < len; ++i) v_next[i] = v[i] + dt_mid * a[i];
}

void advance_displacement(double* __restrict u, double* __restrict du, double* __restrict dtheta,
                          const double* __restrict v, const double* __restrict omega, double dt,
                          std::size_t len) {
  for (std::size_t i = 0; i < len; ++i) {
    du[i] = dt * v[i];
#ifdef __FMA__
    // What the compiler makes of u += dt v on its own (contracted), which it no longer does once
    // dt v is also stored: the same bits as before the fused pass.
    u[i] = std::fma(dt, v[i], u[i]);
#else
    u[i] += dt * v[i];
#endif
    dtheta[i] = dt * omega[i];
  }
}

void zero_held(const std::vector<std::uint8_t>& fixed, double* t, double* r, std::size_t i0,
               std::size_t i1) {
  if (fixed.empty()) return;
  for (std::size_t i = i0; i < i1; ++i) {
    const std::uint8_t mask = fixed[i];
    if (mask == 0) continue;
    for (std::size_t d = 0; d < 3; ++d) {
      if (mask & (1u << d)) t[3 * i + d] = 0.0;
      if (mask & (8u << d)) r[3 * i + d] = 0.0;
    }
  }
}

}  // namespace crashlink::integration
