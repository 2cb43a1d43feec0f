// The solver's rigid walls (model::RigidWall): fixed or moving stonewalls, planes (infinite or
// finite) and cylinders, and their reactions' work.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

/// Rigid walls ([LSTM] stonewalls): a node whose step x^{n+1} = x^n + dt v^{n+1/2} would cross
/// the plane (signed distance d^{n+1} = d^n + dt v.n < 0) gets the normal velocity -max(d^n, 0) /
/// dt: it lands on the plane (a node already behind it stops there); the tangential velocity is
/// kept (frictionless), a node moving away is free. The wall's reaction R^n = m (v^{n+1/2} -
/// v_free^{n+1/2}) / dt_pair works by the trapezoid rule over [t^{n-1}, t^n], as a prescribed
/// velocity's (energy.h): W += 1/2 (R^{n-1} + R^n) . (u^n - u^{n-1}); a node stopped from v_n
/// gives up 1/2 m v_n^2 there (the perfectly plastic impact of a node).
void Solver::apply_rigid_walls(double dt_pair) {
  const double dt = dt_;
  for (auto& rw : walls_) {
    const model::RigidWall& w = *rw.wall;
    rw.force_N = Vec3{};
    wall_gaps(rw);
    // the gap d_i at t^n and the normal n_i of each node (wall_gaps; d_i = NaN: not over the
    // wall); a node stays on its side over the step when v_i.n_i >= V - d_i / dt (V the wall's
    // velocity over the step)
    const auto gap = [&](std::size_t k) { return rw.gap[4 * k]; };
    const auto v_normal = [&](std::size_t k, std::size_t i) {
      return v_[3 * i] * rw.gap[4 * k + 1] + v_[3 * i + 1] * rw.gap[4 * k + 2] +
             v_[3 * i + 2] * rw.gap[4 * k + 3];
    };
    double V = rw.velocity_m_s;
    if (w.moving()) {
      // A moving wall of mass M meets the nodes it would pass in a perfectly plastic impact
      // along its normal: those nodes end the step on the plane, v_i.n = V' - d_i / dt, and the
      // normal momentum is kept, M V + sum m_i v_i.n = M V' + sum m_i (V' - d_i / dt), so
      //   V' = (M V + sum_active m_i (v_i.n + d_i / dt)) / (M + sum_active m_i),
      // the active nodes those with v_i.n < V' - d_i / dt (found by iterating from V' = V: a
      // lighter wall slows, so the set can only shrink; a few passes).
      const double M = w.mass_kg;
      double V_new = V;
      for (int pass = 0; pass < 50; ++pass) {
        double num = M * V, den = M;
        for (std::size_t k = 0; k < w.nodes.size(); ++k) {
          const auto i = static_cast<std::size_t>(w.nodes[k]);
          const double d = std::max(gap(k), 0.0);
          const double vn = v_normal(k, i);
          if (std::isfinite(gap(k)) && vn < V_new - d / dt) {
            num += mass_[i] * (vn + d / dt);
            den += mass_[i];
          }
        }
        const double next = num / den;
        if (next == V_new) break;
        V_new = next;
      }
      V = V_new;
    }
    for (std::size_t k = 0; k < w.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(w.nodes[k]);
      double r[3] = {0.0, 0.0, 0.0};
      const double d = gap(k);
      const double vn = v_normal(k, i);
      const double vn_min = V - std::max(d, 0.0) / dt;
      if (std::isfinite(d) && vn < vn_min) {
        const double dv = vn_min - vn;
        for (std::size_t c = 0; c < 3; ++c) {
          const double nc = rw.gap[4 * k + 1 + c];
          v_[3 * i + c] += dv * nc;
          r[c] = mass_[i] * dv * nc / dt_pair;
        }
      }
      double work = 0.0;
      for (std::size_t c = 0; c < 3; ++c) {
        double& rp = rw.reaction_prev[3 * k + c];
        work += 0.5 * (rp + r[c]) * du_[3 * i + c];
        rp = r[c];
        rw.force_N[c] += r[c];
      }
      if (cycle_ > 0) {
        energy_.external_work_J += work;
        rw.work_J += work;
      }
    }
    rw.velocity_m_s = V;
  }
}

/// Each node's gap to the wall at t^n and the wall's normal there, into rw.gap [4 per node: d,
/// n]. Plane: d = (x - p).n - travel. Finite plane: the same where the node's foot lies on the
/// rectangle, 0 <= (x - p).e <= L, 0 <= (x - p).(n x e) <= W. Cylinder: d = |rho| - R, n =
/// rho / |rho|, rho = r - (r.a) a the node's offset from the axis (r = x - p, a the axis),
/// where 0 <= r.a <= L if finite. A finite wall or a cylinder leaves a node free (d = NaN)
/// outside its extent, or behind it by more than 1e-6 of its size (a node that went round its
/// edge); an infinite plane stops every node.
void Solver::wall_gaps(WallRuntime& rw) const {
  const model::RigidWall& w = *rw.wall;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool cylinder = w.shape == model::RigidWall::Shape::Cylinder;
  const double size = cylinder ? w.radius_m : w.length_m + w.width_m;
  const double behind = -1e-6 * size;
  const Vec3 across = cross(w.normal, w.edge);
  for (std::size_t k = 0; k < w.nodes.size(); ++k) {
    const auto i = static_cast<std::size_t>(w.nodes[k]);
    const Vec3 r = Vec3{x_[3 * i], x_[3 * i + 1], x_[3 * i + 2]} - w.point_m;
    double* g = &rw.gap[4 * k];
    if (!cylinder) {
      g[0] = dot(r, w.normal) - rw.travel_m;
      for (std::size_t c = 0; c < 3; ++c) g[1 + c] = w.normal[c];
      if (w.finite()) {
        const double a = dot(r, w.edge), b = dot(r, across);
        if (a < 0.0 || a > w.length_m || b < 0.0 || b > w.width_m || g[0] < behind) g[0] = nan;
      }
      continue;
    }
    const double s = dot(r, w.normal);
    const Vec3 rho = r - s * w.normal;
    const double dist = norm(rho);
    g[0] = dist - w.radius_m;
    for (std::size_t c = 0; c < 3; ++c) g[1 + c] = dist > 0.0 ? rho[c] / dist : 0.0;
    if (!(dist > 0.0) || g[0] < behind || (w.finite() && (s < 0.0 || s > w.length_m))) g[0] = nan;
  }
}

}  // namespace crashlink::integration
