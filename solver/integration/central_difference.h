#pragma once
// Central differences with variable steps, [2] of Bourel 2005 — free functions over flat arrays.
//   v^{n+1/2} = v^{n-1/2} + dt^{n-1/2} a^n,   dt^{n-1/2} = (dt^{n-1} + dt^n) / 2
//   u^{n+1}   = u^n + dt^n v^{n+1/2}
// Layout: every array is interleaved xyz of length 3n (n nodes).
#include <cstddef>

namespace crashlink::integration {

/// dt^{n-1/2} = (dt^{n-1} + dt^n)/2 ([2]); at the first cycle dt^{-1} = 0, so dt^{-1/2} = dt^0/2
/// (the half-step start v^{1/2} = v^0 + dt^0/2 a^0).
inline double mid_step(double dt_prev, double dt) {
  return 0.5 * (dt_prev + dt);
}

/// v[i] += dt_mid * a[i] for i < len. [2]
void update_velocity(double* v, const double* a, double dt_mid, std::size_t len);

/// u[i] += dt * v[i] for i < len. [2]
void update_displacement(double* u, const double* v, double dt, std::size_t len);

/// a[3i+k] = (f_ext[3i+k] - f_int[3i+k]) * inv_mass[i]: the nodal equation of motion [1] with a
/// lumped mass (inv_mass 0 for massless or rigid-body nodes).
void compute_acceleration(double* a, const double* f_ext, const double* f_int,
                          const double* inv_mass, std::size_t n_nodes);

}  // namespace crashlink::integration
