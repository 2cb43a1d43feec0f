// The solver's planar rigid walls (model::RigidWall): fixed or moving stonewalls and their
// reactions' work.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solver/core/errors.h"
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
    const Vec3& nrm = w.normal;
    rw.force_N = Vec3{};
    // the plane at t^n: point + travel n; a node i stays on its side over the step when
    // v_i.n >= V - d_i / dt (V the wall's velocity over the step)
    auto gap = [&](std::size_t i) {
      return (x_[3 * i] - w.point_m[0]) * nrm[0] + (x_[3 * i + 1] - w.point_m[1]) * nrm[1] +
             (x_[3 * i + 2] - w.point_m[2]) * nrm[2] - rw.travel_m;
    };
    auto v_normal = [&](std::size_t i) {
      return v_[3 * i] * nrm[0] + v_[3 * i + 1] * nrm[1] + v_[3 * i + 2] * nrm[2];
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
        for (auto c : w.nodes) {
          const auto i = static_cast<std::size_t>(c);
          const double d = std::max(gap(i), 0.0);
          const double vn = v_normal(i);
          if (std::isfinite(d) && vn < V_new - d / dt) {
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
      const double d = gap(i);
      const double vn = v_normal(i);
      const double vn_min = V - std::max(d, 0.0) / dt;
      if (std::isfinite(d) && vn < vn_min) {
        const double dv = vn_min - vn;
        for (std::size_t c = 0; c < 3; ++c) {
          v_[3 * i + c] += dv * nrm[c];
          r[c] = mass_[i] * dv * nrm[c] / dt_pair;
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

}  // namespace crashlink::integration
