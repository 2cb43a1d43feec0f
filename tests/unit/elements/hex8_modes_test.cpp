// Mode form of the hexahedron (hex8_modes.h) against the per-node formulas of hex8_geometry.h:
// the Walsh-Hadamard transform and its transpose (M1), the volume gradient (M2) and the hourglass
// vectors and their Gram matrix (M5, M7), on distorted hexahedra. All exact identities: round-off
// tolerances (1e-13 relative).
#include "solver/elements/hex8_modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/elements/hex8_geometry.h"

namespace {

namespace hx = crashlink::elements::hex8;
using hx::kPhi;

void distorted_hex(double (&x)[3][8][1], unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) x[i][I][0] = 0.5 * (kPhi[i][I] + 1.0) + u(gen);
}

}  // namespace

// U_k = sum_I phi_k(I) u_I, and the transpose gives sum_k phi_k(I) U_k = 8 u_I - sum_J u_J.
TEST(Hex8Modes, TransformAndTransposeMatchTheBasis) {
  std::mt19937 gen(2);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  double u[8], m[7], back[8], sum = 0.0;
  for (double& ui : u) {
    ui = d(gen);
    sum += ui;
  }
  hx::analyse(u, m);
  for (int k = 0; k < 7; ++k) {
    double s = 0.0;
    for (int I = 0; I < 8; ++I) s += kPhi[k][I] * u[I];
    EXPECT_NEAR(m[k], s, 1e-14) << "mode " << k;
  }
  hx::synthesise(m, back);
  for (int I = 0; I < 8; ++I) EXPECT_NEAR(back[I], 8.0 * u[I] - sum, 1e-14) << "node " << I;
}

// V and b_I = 1/8 sum_k phi_k(I) g_k (M2) equal volume_gradient; the hourglass vectors
// gamma_alpha = Gamma_alpha - sum_k c_alpha,k phi_k (M5) equal hourglass_vectors, and so does
// their Gram matrix (M7).
TEST(Hex8Modes, GradientAndHourglassVectorsMatchNodalFormulas) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    double x[3][8][1], b[3][8][1], gx[4][3][1], vol[1], gamma[4][8][1];
    distorted_hex(x, seed);
    hx::volume_gradient<1>(x, b, gx, vol);
    hx::hourglass_vectors<1>(b, gx, vol, gamma);

    double X[7][3], g[6][3];
    for (int i = 0; i < 3; ++i) {
      double u[8], m[7];
      for (int I = 0; I < 8; ++I) u[I] = x[i][I][0];
      hx::analyse(u, m);
      for (int k = 0; k < 7; ++k) X[k][i] = m[k];
    }
    const double V = hx::mode_volume_gradient(X, g);
    EXPECT_NEAR(V, vol[0], 1e-13 * vol[0]);
    for (int i = 0; i < 3; ++i) {
      double m[7] = {g[0][i], g[1][i], g[2][i], g[3][i], g[4][i], g[5][i], 0.0}, bi[8];
      hx::synthesise(m, bi);
      for (int I = 0; I < 8; ++I) EXPECT_NEAR(bi[I] / 8.0, b[i][I][0], 1e-13) << "seed " << seed;
    }
    double c[4][6], gam[4][8];
    for (int al = 0; al < 4; ++al) {
      double m[7] = {};
      for (int k = 0; k < 6; ++k) {
        c[al][k] = 0.0;
        for (int i = 0; i < 3; ++i) c[al][k] += X[3 + al][i] / (8.0 * V) * g[k][i];
        m[k] = -c[al][k];
      }
      m[3 + al] += 1.0;
      hx::synthesise(m, gam[al]);
      for (int I = 0; I < 8; ++I) EXPECT_NEAR(gam[al][I], gamma[al][I][0], 1e-13);
    }
    for (int al = 0; al < 4; ++al)
      for (int be = 0; be < 4; ++be) {
        double nodal = 0.0, modal = (al == be) ? 1.0 : 0.0;
        for (int I = 0; I < 8; ++I) nodal += gamma[al][I][0] * gamma[be][I][0];
        if (al < 3) modal -= c[be][3 + al];
        if (be < 3) modal -= c[al][3 + be];
        for (int k = 0; k < 6; ++k) modal += c[al][k] * c[be][k];
        EXPECT_NEAR(8.0 * modal, nodal, 1e-13 * 8.0);
      }
  }
}
