#pragma once
// Mode form of the one-point hexahedron of Flanagan & Belytschko 1981 (FB, IJNME 17, 679-706),
// used by the kernel (hex8.cpp) so that it never forms per-node gradient or hourglass vectors.
// Nodal values u_I of a field are replaced by their modes, their sums against the vectors phi_k(I)
// of hex8_geometry.h (analyse, M1); with phi_k . phi_m = 8 delta_km every FB sum over the nodes
// becomes a sum over modes. The identities used (M1-M8) are on the functions and on the phases of
// the kernel (hex8.cpp) that compute them.
//
// Functions are templates over the number type T (double, or the lane vector vd of hex8_simd.h).
#include "solver/elements/hex8_simd.h"

namespace crashlink::elements::hex8 {

/// Modes U_k = sum_I phi_k(I) u_I, k = 0..6, of nodal values u (LS-DYNA order), with phi_k of
/// hex8_geometry.h (k = 0..6: xi, eta, zeta, eta zeta, zeta xi, xi eta, xi eta zeta at the nodes;
/// with the constant vector 1 an orthogonal basis of R^8, phi_k . phi_m = 8 delta_km):
///   U_k = sum_I phi_k(I) u_I,      u_I = 1/8 (U_c + sum_k phi_k(I) U_k),  U_c = sum_I u_I    (M1)
/// computed by a three-stage Walsh-Hadamard transform (24 additions per component instead of 56
/// multiply-adds). The constant mode U_c is not formed. Face nodes j = 0..3 sit at (xi, eta) =
/// (-,-), (+,-), (+,+), (-,+); node j + 4 is above node j.
template <class T>
inline void analyse(const T (&u)[8], T (&m)[7]) {
  // zeta stage: s_j even, d_j odd in zeta
  const T s0 = u[4] + u[0], s1 = u[5] + u[1], s2 = u[6] + u[2], s3 = u[7] + u[3];
  const T d0 = u[4] - u[0], d1 = u[5] - u[1], d2 = u[6] - u[2], d3 = u[7] - u[3];
  // (xi, eta) stages on both faces
  const T sp = s2 + s0, sq = s2 - s0, sr = s1 + s3, st = s1 - s3;
  const T dp = d2 + d0, dq = d2 - d0, dr = d1 + d3, ds = d1 - d3;
  m[0] = sq + st;  // xi
  m[1] = sq - st;  // eta
  m[2] = dp + dr;  // zeta
  m[3] = dq - ds;  // eta zeta
  m[4] = dq + ds;  // zeta xi
  m[5] = sp - sr;  // xi eta
  m[6] = dp - dr;  // xi eta zeta
}

/// Nodal values u_I = sum_{k=0..6} phi_k(I) m_k (no constant mode): the transpose of analyse. The
/// kernel synthesises the internal forces with it (M8, hex8.cpp); their modes F have no constant
/// mode, so the forces have zero resultant by construction.
template <class T>
inline void synthesise(const T (&m)[7], T (&u)[8]) {
  // zeta-even face from (xi, eta, xi eta) = m0, m1, m5
  const T xpe = m[0] + m[1], xme = m[0] - m[1];
  const T s0 = m[5] - xpe, s1 = xme - m[5], s2 = m[5] + xpe, s3 = -(xme + m[5]);
  // zeta-odd face from (zeta, zeta xi, eta zeta, xi eta zeta) = m2, m4, m3, m6
  const T cp = m[2] + m[6], cm = m[2] - m[6], dpe = m[4] + m[3], dme = m[4] - m[3];
  const T d0 = cp - dpe, d1 = cm + dme, d2 = cp + dpe, d3 = cm - dme;
  u[0] = s0 - d0;
  u[1] = s1 - d1;
  u[2] = s2 - d2;
  u[3] = s3 - d3;
  u[4] = s0 + d0;
  u[5] = s1 + d1;
  u[6] = s2 + d2;
  u[7] = s3 + d3;
}

/// g_k = dV/da_k (k = 0..5 for a1..a6, hex8_geometry.h) from the coordinate modes X (X[k][i],
/// k = 0..N-1, N >= 6; X_k = 8 a_k with the a_k of hex8_geometry.h, so Gamma_alpha . x =
/// X_{3+alpha}); returns the exact volume V = a1 . dV/da1 + a4 . dV/da4. The volume gradient in
/// the mode form:
///   b_I = dV/dx_I = 1/8 sum_{k=0..5} phi_k(I) g_k                                          (M2)
/// With a = X/8 the factors 8 and 8/3 of hex8_geometry.h become 8/64 and 8/(3*64).
template <class T, int N>
inline T mode_volume_gradient(const T (&X)[N][3], T (&g)[6][3]) {
  static_assert(N >= 6, "needs the modes X1..X6");
  const T c1(8.0 / 64.0), c3(8.0 / (3.0 * 64.0));
  // component i of X_p x X_q
  auto cx = [&](int p, int q, int i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    return madd(X[p][j], X[q][k], -(X[p][k] * X[q][j]));
  };
  CRASHLINK_HEX8_UNROLL
  for (int i = 0; i < 3; ++i) {
    g[0][i] = madd(c1, cx(1, 2, i), c3 * cx(5, 4, i));
    g[1][i] = madd(c1, cx(2, 0, i), c3 * cx(3, 5, i));
    g[2][i] = madd(c1, cx(0, 1, i), c3 * cx(4, 3, i));
    g[3][i] = c3 * (cx(2, 4, i) + cx(5, 1, i));
    g[4][i] = c3 * (cx(0, 5, i) + cx(3, 2, i));
    g[5][i] = c3 * (cx(4, 0, i) + cx(1, 3, i));
  }
  T v = X[0][0] * g[0][0];
  v = madd(X[0][1], g[0][1], v);
  v = madd(X[0][2], g[0][2], v);
  v = madd(X[3][0], g[3][0], v);
  v = madd(X[3][1], g[3][1], v);
  v = madd(X[3][2], g[3][2], v);
  return T(0.125) * v;
}

}  // namespace crashlink::elements::hex8
