#pragma once
// Central differences with variable steps, [2] of Bourel 2005 — free functions over flat arrays.
//   v^{n+1/2} = v^{n-1/2} + dt^{n-1/2} a^n,   dt^{n-1/2} = (dt^{n-1} + dt^n) / 2
//   u^{n+1}   = u^n + dt^n v^{n+1/2}
// Layout: every array is interleaved xyz of length 3n (n nodes). Each function is one pass over
// its arrays: the nodal updates are memory-bound, so a pass saved is time saved
// (bench/bench_cycle.cpp).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace crashlink::integration {

/// dt^{n-1/2} = (dt^{n-1} + dt^n)/2 ([2]); at the first cycle dt^{-1} = 0, so dt^{-1/2} = dt^0/2
/// (the half-step start v^{1/2} = v^0 + dt^0/2 a^0).
inline double mid_step(double dt_prev, double dt) {
  return 0.5 * (dt_prev + dt);
}

/// v_prev[i] = v[i], then v[i] += dt_mid * a[i], for i < len: v^{n-1/2} kept, v^{n+1/2} made. [2]
void advance_velocity(double* v, double* v_prev, const double* a, double dt_mid, std::size_t len);

/// v_next[i] = v[i] + dt_mid * a[i], for i < len: v^{n+1/2} made in another buffer, v^{n-1/2}
/// left where it is (the caller swaps the two: one store stream fewer than advance_velocity). [2]
void advance_velocity_into(double* v_next, const double* v, const double* a, double dt_mid,
                           std::size_t len);

/// du[i] = dt * v[i], u[i] += dt * v[i] and dtheta[i] = dt * omega[i], for i < len. [2]
void advance_displacement(double* u, double* du, double* dtheta, const double* v,
                          const double* omega, double dt, std::size_t len);

/// Zeroes the held dofs of nodes [i0, i1): translations (bits 0-2 of fixed[i]) in t, rotations
/// (bits 3-5) in r; fixed empty: none held.
void zero_held(const std::vector<std::uint8_t>& fixed, double* t, double* r, std::size_t i0,
               std::size_t i1);

}  // namespace crashlink::integration
