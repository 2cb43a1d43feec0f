#pragma once
// Reference geometry of single elements for the mesh generator tests: naive, independent of the
// element kernels. Hex8 nodes in LS-DYNA order, Shell4 counter-clockwise (solver/model/model.h).
#include <array>
#include <cmath>
#include <cstdint>

#include "core/vec3.h"
#include "solver/model/model.h"

namespace crashlink::model::testing {

inline Vec3 node_x(const Model& m, std::int32_t i) {
  const auto k = static_cast<std::size_t>(i);
  return {m.nodes.x0[3 * k], m.nodes.x0[3 * k + 1], m.nodes.x0[3 * k + 2]};
}

/// Element e's corner coordinates.
template <int K>
std::array<Vec3, K> corners(const Model& m, const Part& p, std::size_t e) {
  std::array<Vec3, K> x{};
  for (std::size_t a = 0; a < static_cast<std::size_t>(K); ++a)
    x[a] = node_x(m, p.connectivity[K * e + a]);
  return x;
}

/// Smallest corner Jacobian det(x_b - x_a, x_c - x_a, x_d - x_a) of a hexahedron; > 0 for a
/// valid, positively oriented element. The three edge neighbours of each corner, ordered so that
/// the unit cube gives +1 everywhere:
inline double min_corner_jacobian(const std::array<Vec3, 8>& x) {
  static constexpr int nb[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                   {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  double jmin = 1e300;
  for (int a = 0; a < 8; ++a) {
    const Vec3 e1 = x[static_cast<std::size_t>(nb[a][0])] - x[static_cast<std::size_t>(a)];
    const Vec3 e2 = x[static_cast<std::size_t>(nb[a][1])] - x[static_cast<std::size_t>(a)];
    const Vec3 e3 = x[static_cast<std::size_t>(nb[a][2])] - x[static_cast<std::size_t>(a)];
    jmin = std::min(jmin, dot(e1, cross(e2, e3)));
  }
  return jmin;
}

/// Volume of a trilinear hexahedron: 2x2x2 Gauss quadrature of det J (exact for it).
inline double hex_volume(const std::array<Vec3, 8>& x) {
  static constexpr double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double g = 1.0 / std::sqrt(3.0);
  double v = 0.0;
  for (double xi : {-g, g})
    for (double eta : {-g, g})
      for (double zeta : {-g, g}) {
        Vec3 d[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // dx/dxi, dx/deta, dx/dzeta
        for (std::size_t a = 0; a < 8; ++a) {
          const double sa = s[a][0], ta = s[a][1], ua = s[a][2];
          d[0] = d[0] + (0.125 * sa * (1 + ta * eta) * (1 + ua * zeta)) * x[a];
          d[1] = d[1] + (0.125 * ta * (1 + sa * xi) * (1 + ua * zeta)) * x[a];
          d[2] = d[2] + (0.125 * ua * (1 + sa * xi) * (1 + ta * eta)) * x[a];
        }
        v += dot(d[0], cross(d[1], d[2]));
      }
  return v;
}

/// Area of a bilinear quadrilateral: 2x2 Gauss quadrature of |x_xi x x_eta|.
inline double quad_area(const std::array<Vec3, 4>& x) {
  const double g = 1.0 / std::sqrt(3.0);
  double a = 0.0;
  for (double xi : {-g, g})
    for (double eta : {-g, g}) {
      const Vec3 dxi = (0.25 * (1 - eta)) * (x[1] - x[0]) + (0.25 * (1 + eta)) * (x[2] - x[3]);
      const Vec3 deta = (0.25 * (1 - xi)) * (x[3] - x[0]) + (0.25 * (1 + xi)) * (x[2] - x[1]);
      a += norm(cross(dxi, deta));
    }
  return a;
}

/// Unit normal of a quadrilateral from its diagonals: (x2 - x0) x (x3 - x1), normalised.
inline Vec3 quad_normal(const std::array<Vec3, 4>& x) {
  const Vec3 n = cross(x[2] - x[0], x[3] - x[1]);
  return (1.0 / norm(n)) * n;
}

/// Smallest corner cross product (x_next - x_a) x (x_prev - x_a) . n: > 0 for a convex quad
/// oriented counter-clockwise around n.
inline double min_corner_turn(const std::array<Vec3, 4>& x, const Vec3& n) {
  double m = 1e300;
  for (std::size_t a = 0; a < 4; ++a)
    m = std::min(m, dot(cross(x[(a + 1) % 4] - x[a], x[(a + 3) % 4] - x[a]), n));
  return m;
}

}  // namespace crashlink::model::testing
