#pragma once
// Geometry of the 8-node hexahedron for the one-point (uniform strain) element of Flanagan &
// Belytschko 1981 ("A uniform strain hexahedron and quadrilateral with orthogonal hourglass
// control", IJNME 17, 679-706; below "FB"), batched over W elements ("lanes"): the exact volume,
// its gradient (FB's uniform gradient times V) and the hourglass vectors. All arrays are
// lane-innermost so that every loop over l vectorises.
//
// These per-node forms serve hex8_lumped_mass and the tests (the reference of the force kernel);
// the force kernel evaluates the same quantities in the mode form of hex8_modes.h.

namespace crashlink::elements::hex8 {

/// Natural coordinates of the nodes (LS-DYNA order) and the products phi_k(I): xi, eta, zeta,
/// eta zeta, zeta xi, xi eta, xi eta zeta at the nodes, values +-1; the last four are FB's
/// hourglass base vectors Gamma_1..4 (FB eq. 21/Table 1).
inline constexpr double kPhi[7][8] = {
    {-1, 1, 1, -1, -1, 1, 1, -1},   // xi
    {-1, -1, 1, 1, -1, -1, 1, 1},   // eta
    {-1, -1, -1, -1, 1, 1, 1, 1},   // zeta
    {1, 1, -1, -1, -1, -1, 1, 1},   // eta zeta   = Gamma_1 (FB Table 1)
    {1, -1, -1, 1, -1, 1, 1, -1},   // zeta xi    = Gamma_2
    {1, -1, 1, -1, 1, -1, 1, -1},   // xi eta     = Gamma_3
    {-1, 1, -1, 1, 1, -1, 1, -1}};  // xi eta zeta = Gamma_4

/// Volume, volume gradient b = dV/dx and Gamma.x of W hexahedra:
///   x    [3][8][W]  coordinates x_iI of node I (LS-DYNA order, see model.h) of lane l  [m]
///   dvdx [3][8][W]  b_iI = dV/dx_iI (FB's uniform gradient times V, FB eq. 13/16)       [m^2]
///   gx   [4][3][W]  Gamma_alpha . x_i (hourglass base vectors dotted with the coordinates) [m]
///   vol  [W]        exact volume of the trilinear hexahedron V = int det J                [m^3]
/// Exact volume. Write the isoparametric map as
///   x(xi, eta, zeta) = a0 + a1 xi + a2 eta + a3 zeta + a4 eta zeta + a5 zeta xi + a6 xi eta
///                      + a7 xi eta zeta,     a_k = 1/8 sum_I phi_k(I) x_I
/// (phi_k of kPhi). Integrating det J = x_xi . (x_eta x x_zeta) over [-1,1]^3 term by term keeps
/// only monomials of even degree:
///   V = 8 a1.(a2 x a3) + 8/3 [a1.(a6 x a5) + a5.(a4 x a3) + a6.(a2 x a4)]        (a7 drops out)
/// which is the same polynomial as FB eq. 16, grouped differently. Its gradient is
///   dV/da1 = 8 a2 x a3 + 8/3 a6 x a5      dV/da4 = 8/3 (a3 x a5 + a6 x a2)
///   dV/da2 = 8 a3 x a1 + 8/3 a4 x a6      dV/da5 = 8/3 (a1 x a6 + a4 x a3)
///   dV/da3 = 8 a1 x a2 + 8/3 a5 x a4      dV/da6 = 8/3 (a5 x a1 + a2 x a4)
/// and b_I = dV/dx_I = 1/8 sum_k phi_k(I) dV/da_k. B_iI = b_iI / V is FB's uniform-gradient
/// matrix (FB eq. 13): sum_I B_iI x_jI = delta_ij and sum_I B_iI = 0 exactly (V is homogeneous of
/// degree 1 in each coordinate direction and translation invariant), which is what makes the patch
/// test pass on distorted meshes. Gamma_alpha . x = 8 a_{3+alpha}.
template <int W>
inline void volume_gradient(const double (&x)[3][8][W], double (&dvdx)[3][8][W],
                            double (&gx)[4][3][W], double (&vol)[W]) {
  double a[7][3][W];  // a_k,i (k = 0..6 for a1..a7)
  for (int k = 0; k < 7; ++k)
    for (int i = 0; i < 3; ++i) {
      for (int l = 0; l < W; ++l) a[k][i][l] = 0.0;
      for (int I = 0; I < 8; ++I) {
        const double p = 0.125 * kPhi[k][I];
        for (int l = 0; l < W; ++l) a[k][i][l] += p * x[i][I][l];
      }
    }
  for (int al = 0; al < 4; ++al)
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < W; ++l) gx[al][i][l] = 8.0 * a[3 + al][i][l];

  double g[6][3][W];  // dV/da_k, k = 0..5
  constexpr double t = 8.0 / 3.0;
  for (int l = 0; l < W; ++l) {
    // cross product c = p x q, components 0..2 (lambda keeps the formulas readable)
    auto cx = [&](int p, int q, int i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      return a[p][j][l] * a[q][k][l] - a[p][k][l] * a[q][j][l];
    };
    for (int i = 0; i < 3; ++i) {
      g[0][i][l] = 8.0 * cx(1, 2, i) + t * cx(5, 4, i);
      g[1][i][l] = 8.0 * cx(2, 0, i) + t * cx(3, 5, i);
      g[2][i][l] = 8.0 * cx(0, 1, i) + t * cx(4, 3, i);
      g[3][i][l] = t * (cx(2, 4, i) + cx(5, 1, i));
      g[4][i][l] = t * (cx(0, 5, i) + cx(3, 2, i));
      g[5][i][l] = t * (cx(4, 0, i) + cx(1, 3, i));
    }
    // V = a1 . dV/da1 + a4 . dV/da4 (expand both: the four terms of V)
    double v = 0.0;
    for (int i = 0; i < 3; ++i) v += a[0][i][l] * g[0][i][l] + a[3][i][l] * g[3][i][l];
    vol[l] = v;
  }
  for (int i = 0; i < 3; ++i)
    for (int I = 0; I < 8; ++I) {
      for (int l = 0; l < W; ++l) dvdx[i][I][l] = 0.0;
      for (int k = 0; k < 6; ++k) {
        const double p = 0.125 * kPhi[k][I];
        for (int l = 0; l < W; ++l) dvdx[i][I][l] += p * g[k][i][l];
      }
    }
}

/// FB hourglass vectors gamma_alpha,I from b = dV/dx, Gamma.x and V, orthogonal to the linear
/// field (FB eq. 22):
///   gamma_alpha = Gamma_alpha - (Gamma_alpha . x_i) B_i,  B = b / V,  so gamma.1 = 0 and
///   gamma.x_j = 0.
template <int W>
inline void hourglass_vectors(const double (&dvdx)[3][8][W], const double (&gx)[4][3][W],
                              const double (&vol)[W], double (&gamma)[4][8][W]) {
  double inv_v[W];
  for (int l = 0; l < W; ++l) inv_v[l] = 1.0 / vol[l];
  for (int al = 0; al < 4; ++al)
    for (int I = 0; I < 8; ++I)
      for (int l = 0; l < W; ++l)
        gamma[al][I][l] = kPhi[3 + al][I] -
                          inv_v[l] * (gx[al][0][l] * dvdx[0][I][l] + gx[al][1][l] * dvdx[1][I][l] +
                                      gx[al][2][l] * dvdx[2][I][l]);
}

}  // namespace crashlink::elements::hex8
