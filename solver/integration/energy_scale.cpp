#include "solver/integration/energy_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/integration/solver.h"

namespace crashlink::integration {

double model_energy_scale_J(const Solver& s) {
  const model::Model& m = s.model();
  const std::size_t n = m.nodes.count();
  std::vector<std::uint8_t> skip(n, 0);  // rigid and ghost nodes: their energy is elsewhere
  for (const auto& b : s.rigid_bodies())
    for (auto i : b.nodes) skip[static_cast<std::size_t>(i)] = 1;
  for (auto g : s.ghost_nodes()) skip[static_cast<std::size_t>(g)] = 1;
  const auto& v = s.velocity_mid();  // v^0 after initialize()
  const auto& w = s.angular_velocity_mid();
  double twice = 0.0;  // 2 E
  for (std::size_t i = 0; i < n; ++i) {
    if (skip[i]) continue;
    for (std::size_t d = 0; d < 3; ++d)
      twice +=
          s.mass()[i] * v[3 * i + d] * v[3 * i + d] + s.inertia()[i] * w[3 * i + d] * w[3 * i + d];
  }
  for (const auto& b : s.rigid_bodies()) {
    twice += b.mass_kg * dot(b.velocity, b.velocity);
    twice += dot(b.omega, mul(b.inertia_body, b.omega));
  }
  for (const auto& p : m.prescribed_velocities) {
    double peak = 0.0;
    for (double x : p.velocity.value) peak = std::max(peak, std::abs(x));
    if (p.rigid_body >= 0) {  // a body's: its mass, or its largest moment of inertia
      const auto& b = s.rigid_bodies()[static_cast<std::size_t>(p.rigid_body)];
      const double j = std::max({b.inertia_body[0][0], b.inertia_body[1][1], b.inertia_body[2][2]});
      twice += (p.dof < 3 ? b.mass_kg : j) * peak * peak;
      continue;
    }
    const auto& per_node = p.dof < 3 ? s.mass() : s.inertia();
    for (auto i : p.nodes) twice += per_node[static_cast<std::size_t>(i)] * peak * peak;
  }
  return 0.5 * twice;
}

}  // namespace crashlink::integration
