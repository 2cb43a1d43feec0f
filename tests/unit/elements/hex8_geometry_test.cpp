// Geometry of the one-point hexahedron: exact volume, uniform gradient b = dV/dx (FB eq. 13/16),
// hourglass vectors (FB eq. 22), lumped mass. References are computed independently here
// (2x2x2 Gauss quadrature of det J, central differences of the volume).
#include "solver/elements/hex8_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/errors.h"
#include "solver/elements/hex8.h"

namespace {

using crashlink::elements::hex8::kPhi;

// A distorted hexahedron: unit cube (LS-DYNA order) with nodes moved by up to 0.25.
void distorted_hex(double (&x)[3][8][1], unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) x[i][I][0] = 0.5 * (kPhi[i][I] + 1.0) + u(gen);
}

// Volume by 2x2x2 Gauss quadrature of det J: exact, since det J is at most quadratic in each
// natural coordinate.
double gauss_volume(const double (&x)[3][8][1]) {
  const double g = 1.0 / std::sqrt(3.0);
  double vol = 0.0;
  for (int p = 0; p < 8; ++p) {
    const double xi = (p & 1 ? g : -g), eta = (p & 2 ? g : -g), zeta = (p & 4 ? g : -g);
    double J[3][3] = {};
    for (int I = 0; I < 8; ++I) {
      const double dn[3] = {0.125 * kPhi[0][I] * (1 + eta * kPhi[1][I]) * (1 + zeta * kPhi[2][I]),
                            0.125 * kPhi[1][I] * (1 + xi * kPhi[0][I]) * (1 + zeta * kPhi[2][I]),
                            0.125 * kPhi[2][I] * (1 + xi * kPhi[0][I]) * (1 + eta * kPhi[1][I])};
      for (int i = 0; i < 3; ++i)
        for (int r = 0; r < 3; ++r) J[i][r] += x[i][I][0] * dn[r];
    }
    vol += J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
           J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
           J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  }
  return vol;
}

double volume(const double (&x)[3][8][1]) {
  double b[3][8][1], gx[4][3][1], v[1];
  crashlink::elements::hex8::volume_gradient<1>(x, b, gx, v);
  return v[0];
}

}  // namespace

// Exact integration on both sides: only round-off differs (1e-13 relative).
TEST(Hex8Geometry, VolumeEqualsGaussQuadratureOfDetJ) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    double x[3][8][1];
    distorted_hex(x, seed);
    EXPECT_NEAR(volume(x), gauss_volume(x), 1e-13 * gauss_volume(x)) << "seed " << seed;
  }
}

// V is a cubic polynomial in the coordinates: central differences with h = 1e-5 have truncation
// error h^2 * O(1) = 1e-10 and round-off 1e-16 / h ~ 1e-11 (tolerance 1e-8 absolute, V ~ 1).
TEST(Hex8Geometry, GradientIsDerivativeOfVolumeAndReproducesLinearFields) {
  double x[3][8][1];
  distorted_hex(x, 7);
  double b[3][8][1], gx[4][3][1], v[1];
  crashlink::elements::hex8::volume_gradient<1>(x, b, gx, v);
  const double h = 1e-5;
  for (int i = 0; i < 3; ++i)
    for (int I = 0; I < 8; ++I) {
      double xp[3][8][1], xm[3][8][1];
      std::copy(&x[0][0][0], &x[0][0][0] + 24, &xp[0][0][0]);
      std::copy(&x[0][0][0], &x[0][0][0] + 24, &xm[0][0][0]);
      xp[i][I][0] += h;
      xm[i][I][0] -= h;
      EXPECT_NEAR(b[i][I][0], (volume(xp) - volume(xm)) / (2 * h), 1e-8);
    }
  // sum_I B_iI x_jI = delta_ij and sum_I B_iI = 0 (FB eq. 14): round-off, 1e-13
  for (int i = 0; i < 3; ++i) {
    double s1 = 0.0;
    for (int I = 0; I < 8; ++I) s1 += b[i][I][0];
    EXPECT_NEAR(s1 / v[0], 0.0, 1e-13);
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int I = 0; I < 8; ++I) s += b[i][I][0] * x[j][I][0];
      EXPECT_NEAR(s / v[0], i == j ? 1.0 : 0.0, 1e-13);
    }
  }
  // hourglass vectors are orthogonal to the constant and linear fields (FB eq. 22): round-off
  double gamma[4][8][1];
  crashlink::elements::hex8::hourglass_vectors<1>(b, gx, v, gamma);
  for (int al = 0; al < 4; ++al) {
    double s1 = 0.0;
    for (int I = 0; I < 8; ++I) s1 += gamma[al][I][0];
    EXPECT_NEAR(s1, 0.0, 1e-13);
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int I = 0; I < 8; ++I) s += gamma[al][I][0] * x[j][I][0];
      EXPECT_NEAR(s, 0.0, 1e-13);
    }
  }
}

// Total lumped mass equals rho V (round-off, 1e-12 relative); an inverted element is reported with
// its user id, part name and volume.
TEST(Hex8Geometry, LumpedMassAndInvertedElement) {
  crashlink::model::Part part;
  part.name = "block";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {42};
  crashlink::materials::Material mat{
      "steel", crashlink::materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
  double x[3][8][1];
  distorted_hex(x, 3);
  std::vector<double> x0(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) x0[3 * I + i] = x[i][I][0];
  std::vector<double> mass(8, 1.0);
  crashlink::elements::hex8_lumped_mass(part, mat, x0.data(), mass.data());
  double total = 0.0;
  for (double m : mass) total += m - 1.0;
  EXPECT_NEAR(total, 7850.0 * gauss_volume(x), 1e-12 * total);

  part.connectivity = {4, 5, 6, 7, 0, 1, 2, 3};  // upside down: negative volume
  try {
    crashlink::elements::hex8_lumped_mass(part, mat, x0.data(), mass.data());
    FAIL() << "inverted element accepted";
  } catch (const crashlink::NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("42"), std::string::npos) << what;
    EXPECT_NE(what.find("block"), std::string::npos) << what;
  }
}
