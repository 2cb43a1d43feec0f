#include "core/vec3.h"

namespace crashlink {

double determinant(const Mat3& a) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  return a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
}

/// The adjugate over the determinant.
Mat3 inverse(const Mat3& a) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double s = 1.0 / determinant(a);
  Mat3 r{};
  r[0][0] = c00 * s;
  r[1][0] = c01 * s;
  r[2][0] = c02 * s;
  r[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * s;
  r[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * s;
  r[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * s;
  r[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * s;
  r[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * s;
  r[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * s;
  return r;
}

Mat3 rotation_from_vector(const Vec3& w) {
  // Rodrigues: R = I + sin(th)/th [w]x + (1-cos(th))/th^2 [w]x^2, series near th = 0.
  const double th2 = dot(w, w);
  const double th = std::sqrt(th2);
  double s, c;
  if (th < 1e-6) {
    s = 1.0 - th2 / 6.0;
    c = 0.5 - th2 / 24.0;
  } else {
    s = std::sin(th) / th;
    c = (1.0 - std::cos(th)) / th2;
  }
  const Mat3 k{{{0, -w[2], w[1]}, {w[2], 0, -w[0]}, {-w[1], w[0], 0}}};
  const Mat3 k2 = mul(k, k);
  Mat3 r = identity3();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] += s * k[i][j] + c * k2[i][j];
  return r;
}

}  // namespace crashlink
