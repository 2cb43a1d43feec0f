// LayerWorkMeter (layer_work.h): the link work of a `layer` interface on the owner's instants.
#include "coupling/layer_work.h"

namespace crashlink::coupling {

LayerSample LayerWorkMeter::add(Tick T, std::span<const double> g, std::span<const double> m,
                                std::span<const double> u, std::span<const double> omega) {
  if (s_.have_prev) {
    // Trapezoid rule on [T - H, T]: 1/2 (g(T - H) + g(T)) . (u(T) - u(T - H)).
    double dw = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i)
      dw += 0.5 * (s_.g_prev[i] + g[i]) * (u[i] - s_.u_prev[i]);
    // Moments: 1/2 (m(T - H) + m(T)) . H omega(T - H/2), as Solver counts them.
    if (!m.empty() && !omega.empty()) {
      for (std::size_t i = 0; i < m.size(); ++i) {
        const double m_prev = s_.m_prev.empty() ? 0.0 : s_.m_prev[i];
        dw += 0.5 * m_prev * (H_s_ * omega[i]);
        dw += 0.5 * m[i] * (H_s_ * omega[i]);
      }
    }
    s_.work_J += dw;
  }
  LayerSample row;
  row.time = T;
  row.link_work_J = s_.work_J;
  for (std::size_t i = 0; i + 2 < g.size(); i += 3)  // the same sums as over i % 3
    for (std::size_t d = 0; d < 3; ++d) row.force_N[d] += g[i + d];
  s_.g_prev.assign(g.begin(), g.end());
  s_.u_prev.assign(u.begin(), u.end());
  s_.m_prev.assign(m.begin(), m.end());
  s_.have_prev = true;
  return row;
}

}  // namespace crashlink::coupling
