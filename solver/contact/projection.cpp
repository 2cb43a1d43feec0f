#include "solver/contact/projection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crashlink::contact {

namespace {

constexpr double kXiA[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEtaA[4] = {-1.0, -1.0, 1.0, 1.0};

/// The bilinear shape functions N_a = (1 + xi xi_a)(1 + eta eta_a)/4.
void bilinear(double xi, double eta, double* N) {
  for (int a = 0; a < 4; ++a) N[a] = 0.25 * (1.0 + xi * kXiA[a]) * (1.0 + eta * kEtaA[a]);
}

/// x_,xi and x_,eta of the bilinear map at (xi, eta): sum_a N_a,xi x_a and sum_a N_a,eta x_a.
void tangents(const double* xa, double xi, double eta, double* t1, double* t2) {
  for (int d = 0; d < 3; ++d) {
    t1[d] = 0.0;
    t2[d] = 0.0;
  }
  for (int a = 0; a < 4; ++a) {
    const double dxi = 0.25 * kXiA[a] * (1.0 + eta * kEtaA[a]);
    const double deta = 0.25 * kEtaA[a] * (1.0 + xi * kXiA[a]);
    for (int d = 0; d < 3; ++d) {
      t1[d] += dxi * xa[3 * a + d];
      t2[d] += deta * xa[3 * a + d];
    }
  }
}

void unit_cross(const double* a, const double* b, double* n) {
  n[0] = a[1] * b[2] - a[2] * b[1];
  n[1] = a[2] * b[0] - a[0] * b[2];
  n[2] = a[0] * b[1] - a[1] * b[0];
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0.0)
    for (int d = 0; d < 3; ++d) n[d] /= l;
}

/// Parameter t in [0, 1] of the closest point to p on the segment a-b, and the squared distance.
double closest_on_edge(const double* a, const double* b, const double* p, double& t) {
  double ab[3], ap[3];
  double ab2 = 0.0, apab = 0.0;
  for (int d = 0; d < 3; ++d) {
    ab[d] = b[d] - a[d];
    ap[d] = p[d] - a[d];
    ab2 += ab[d] * ab[d];
    apab += ap[d] * ab[d];
  }
  // std::min/max with the bound first: a NaN quotient gives the bound, as fmin/fmax do, and it
  // compiles to two instructions (fmin/fmax were calls into libm: 1.8 % of the head impact).
  t = ab2 > 0.0 ? std::min(1.0, std::max(0.0, apab / ab2)) : 0.0;
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double r = ap[d] - t * ab[d];
    r2 += r * r;
  }
  return r2;
}

}  // namespace

Projection project_quad(const double* xa_in, const double* p_in) {
  // Work relative to node 0: keeps the parametric round-off at eps * (segment size), not
  // eps * |x| (a 5 mm segment 5 m from the origin would otherwise never converge to 1e-13).
  double xa[12], p[3];
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d) xa[3 * a + d] = xa_in[3 * a + d] - xa_in[d];
  for (int d = 0; d < 3; ++d) p[d] = p_in[d] - xa_in[d];
  Projection pr;
  double xi = 0.0, eta = 0.0;
  bool converged = false;
  for (int it = 0; it < 20; ++it) {
    double N[4], t1[3], t2[3], r[3];
    bilinear(xi, eta, N);
    tangents(xa, xi, eta, t1, t2);
    for (int d = 0; d < 3; ++d)
      r[d] = p[d] - (N[0] * xa[d] + N[1] * xa[3 + d] + N[2] * xa[6 + d] + N[3] * xa[9 + d]);
    // J = [x_,xi  x_,eta]; H dxi = J^T r
    const double a11 = t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2];
    const double a22 = t2[0] * t2[0] + t2[1] * t2[1] + t2[2] * t2[2];
    // Newton: H = J^T J - (r . x_,xi eta) [[0 1][1 0]] (x_,xi xi = x_,eta eta = 0 for bilinear)
    double rxe = 0.0;
    for (int d = 0; d < 3; ++d) rxe += r[d] * 0.25 * (xa[d] - xa[3 + d] + xa[6 + d] - xa[9 + d]);
    const double a12 = t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2] - rxe;
    const double b1 = t1[0] * r[0] + t1[1] * r[1] + t1[2] * r[2];
    const double b2 = t2[0] * r[0] + t2[1] * r[1] + t2[2] * r[2];
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0)) break;
    const double dxi = (a22 * b1 - a12 * b2) / det;
    const double deta = (a11 * b2 - a12 * b1) / det;
    xi += dxi;
    eta += deta;
    if (std::fabs(xi) > 4.0 || std::fabs(eta) > 4.0) break;  // far outside: use the edges
    if (std::fabs(dxi) + std::fabs(deta) < 1e-11) {          // quadratic: next step ~ round-off
      converged = true;
      break;
    }
  }
  constexpr double kTol = 1e-12;
  if (converged && std::fabs(xi) <= 1.0 + kTol && std::fabs(eta) <= 1.0 + kTol) {
    xi = std::min(1.0, std::max(-1.0, xi));  // finite here (converged)
    eta = std::min(1.0, std::max(-1.0, eta));
    pr.interior = true;
  } else {
    // Boundary: the nearest of the four straight edges a -> a+1.
    double best = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 4; ++e) {
      double t = 0.0;
      const double r2 = closest_on_edge(xa + 3 * e, xa + 3 * ((e + 1) % 4), p, t);
      if (r2 < best) {
        best = r2;
        const double s = -1.0 + 2.0 * t;
        switch (e) {
          case 0:
            xi = s, eta = -1.0;
            break;
          case 1:
            xi = 1.0, eta = s;
            break;
          case 2:
            xi = -s, eta = 1.0;
            break;
          default:
            xi = -1.0, eta = -s;
            break;
        }
      }
    }
  }
  bilinear(xi, eta, pr.N);
  for (int d = 0; d < 3; ++d)
    pr.xc[d] = xa_in[d] +
               (pr.N[0] * xa[d] + pr.N[1] * xa[3 + d] + pr.N[2] * xa[6 + d] + pr.N[3] * xa[9 + d]);
  double t1[3], t2[3];
  tangents(xa, xi, eta, t1, t2);
  unit_cross(t1, t2, pr.normal);
  return pr;
}

Projection project_triangle(const double* xa, const double* p) {
  // Ericson, Real-Time Collision Detection (2005), 5.1.5 ClosestPtPointTriangle.
  Projection pr;
  const double* a = xa;
  const double* b = xa + 3;
  const double* c = xa + 6;
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int d = 0; d < 3; ++d) {
    ab[d] = b[d] - a[d];
    ac[d] = c[d] - a[d];
    ap[d] = p[d] - a[d];
    bp[d] = p[d] - b[d];
    cp[d] = p[d] - c[d];
  }
  auto dot = [](const double* u, const double* w) {
    return u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  };
  unit_cross(ab, ac, pr.normal);
  double u = 0.0, v = 0.0, w = 0.0;  // barycentric weights of a, b, c
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double vc = d1 * d4 - d3 * d2;
  const double vb = d5 * d2 - d1 * d6;
  const double va = d3 * d6 - d5 * d4;
  if (d1 <= 0.0 && d2 <= 0.0) {
    u = 1.0;
  } else if (d3 >= 0.0 && d4 <= d3) {
    v = 1.0;
  } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    v = d1 / (d1 - d3);
    u = 1.0 - v;
  } else if (d6 >= 0.0 && d5 <= d6) {
    w = 1.0;
  } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    w = d2 / (d2 - d6);
    u = 1.0 - w;
  } else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1.0 - w;
  } else {
    const double denom = 1.0 / (va + vb + vc);
    v = vb * denom;
    w = vc * denom;
    u = 1.0 - v - w;
    pr.interior = true;
  }
  pr.N[0] = u;
  pr.N[1] = v;
  pr.N[2] = w;
  for (int d = 0; d < 3; ++d) pr.xc[d] = u * a[d] + v * b[d] + w * c[d];
  return pr;
}

}  // namespace crashlink::contact
