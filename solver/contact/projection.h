#pragma once
// Closest-point projection of a point onto one contact segment (bilinear quad or triangle).
// Sources: Hallquist, LS-DYNA Theory Manual, "Contact-impact algorithm" (quads); Ericson,
// Real-Time Collision Detection, 5.1.5 (triangles). The equations are on project_quad and
// project_triangle.
#include <cstdint>

namespace crashlink::contact {

struct Projection {
  double N[4] = {0.0, 0.0, 0.0,
                 0.0};  ///< shape functions at the closest point (N[3] = 0 for triangles)
  double xc[3] = {0.0, 0.0, 0.0};  ///< closest point [m]
  double normal[3] = {
      0.0, 0.0, 0.0};  ///< unit segment normal at the closest point (orientation of the nodes)
  /// The closest point is inside the segment (not on an edge or a vertex): then p - x_c is
  /// along the segment normal. On an edge or a vertex the caller uses the direction p - x_c
  /// instead, which makes the contact normal continuous when a node slides around a convex edge
  /// and across the boundary between two segments.
  bool interior = false;
};

/// Quad (4 distinct nodes, LS-DYNA shell order), `xa` [12] node coordinates, interleaved xyz,
/// `p` [3]: x(xi, eta) = sum_a N_a x_a with the bilinear
///   N_a = (1 + xi xi_a)(1 + eta eta_a)/4,  (xi_a, eta_a) = (-1,-1), (1,-1), (1,1), (-1,1)
/// (Hallquist, LS-DYNA Theory Manual, "Contact-impact algorithm", the master-segment projection
/// eqs: (p - x(xi,eta)) . x_,xi = 0, (p - x(xi,eta)) . x_,eta = 0). Solved with Newton's method
/// from the centre (exact in one step for a flat parallelogram; the Hessian includes the
/// (p - x) . x_,xi eta term of the warped quad). If the stationary point lies outside [-1,1]^2
/// (or Newton does not converge) the closest point is on the boundary: the four edges are
/// straight, so the closest point of each edge is found exactly and the nearest one is kept; its
/// (xi, eta) lies on the edge, so N_a is the linear edge interpolation.
Projection project_quad(const double* xa, const double* p);
/// Triangle (n3 == n2), `xa` [9] node coordinates, interleaved xyz, `p` [3]: the exact closest
/// point with barycentric regions (Ericson, Real-Time Collision Detection, 5.1.5); N =
/// barycentric coordinates on the three distinct nodes.
Projection project_triangle(const double* xa, const double* p);

}  // namespace crashlink::contact
