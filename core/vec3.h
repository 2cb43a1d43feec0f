#pragma once
// Small fixed-size vector/matrix helpers for per-node and per-body work (not for hot element
// loops, which work on flat arrays). Plain aggregates, value semantics, no heap.
#include <array>
#include <cmath>

namespace crashlink {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<std::array<double, 3>, 3>;  // row-major: m[row][col]

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

inline Vec3 mul(const Mat3& m, const Vec3& x) {
  return {m[0][0] * x[0] + m[0][1] * x[1] + m[0][2] * x[2],
          m[1][0] * x[0] + m[1][1] * x[1] + m[1][2] * x[2],
          m[2][0] * x[0] + m[2][1] * x[1] + m[2][2] * x[2]};
}
inline Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}
inline Mat3 transpose(const Mat3& a) {
  Mat3 t{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t[i][j] = a[j][i];
  return t;
}
inline Mat3 identity3() {
  return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
}

/// Inverse of a 3x3 matrix; the caller guarantees it is regular.
/// det(a) by the first row's cofactors.
double determinant(const Mat3& a);
Mat3 inverse(const Mat3& a);

/// Rotation matrix exp([w]x) for the rotation vector w (Rodrigues' formula), rad.
Mat3 rotation_from_vector(const Vec3& w);

}  // namespace crashlink
