#include "solver/integration/energy_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/integration/solver.h"

namespace crashlink::integration {

double integral_of_magnitude(const model::Curve& c, double t_end_s) {
  const std::size_t n = c.t_s.size();
  if (n == 0 || t_end_s <= 0.0) return 0.0;
  if (n == 1) return std::abs(c.value[0]) * t_end_s;
  // |f| over [t0, t1] for f linear from a to b: the trapezoid when they share a sign, the two
  // triangles on either side of the root otherwise: (t1 - t0)(a^2 + b^2) / (2 (|a| + |b|)).
  auto piece = [](double t0, double t1, double a, double b) {
    const double h = t1 - t0;
    if (h <= 0.0) return 0.0;
    if (a * b >= 0.0) return 0.5 * h * (std::abs(a) + std::abs(b));
    return 0.5 * h * (a * a + b * b) / (std::abs(a) + std::abs(b));
  };
  double sum = std::abs(c.value[0]) * std::min(std::max(c.t_s[0], 0.0), t_end_s);  // before
  for (std::size_t i = 1; i < n && c.t_s[i - 1] < t_end_s; ++i) {
    double t0 = c.t_s[i - 1], t1 = c.t_s[i], a = c.value[i - 1], b = c.value[i];
    if (t1 <= 0.0) continue;
    const double slope = (b - a) / (t1 - t0);  // abscissae strictly increasing
    if (t0 < 0.0) {  // clipped at 0 and at the end time: the curve's values there
      a += slope * (0.0 - t0);
      t0 = 0.0;
    }
    if (t1 > t_end_s) {
      b = a + slope * (t_end_s - t0);
      t1 = t_end_s;
    }
    sum += piece(t0, t1, a, b);
  }
  if (t_end_s > c.t_s[n - 1])
    sum += std::abs(c.value[n - 1]) * (t_end_s - std::max(c.t_s[n - 1], 0.0));  // after
  return sum;
}

namespace {

/// [n] 1 for the nodes a domain's energy leaves out: a rigid body's (its energy is the body's)
/// and ghosts (the owner's).
std::vector<std::uint8_t> skipped_nodes(const Solver& s) {
  std::vector<std::uint8_t> skip(s.model().nodes.count(), 0);
  for (const auto& b : s.rigid_bodies())
    for (auto i : b.nodes) skip[static_cast<std::size_t>(i)] = 1;
  for (auto g : s.ghost_nodes()) skip[static_cast<std::size_t>(g)] = 1;
  return skip;
}

}  // namespace

double model_energy_scale_J(const Solver& s) {
  const model::Model& m = s.model();
  const std::size_t n = m.nodes.count();
  const auto skip = skipped_nodes(s);
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
  return 0.5 * twice + pushed_energy_J(s);
}

double pushed_energy_J(const Solver& s) {
  const model::Model& m = s.model();
  const double t_end_s = m.controls.end_time_s;
  double mass_kg = 0.0;  // the model's: the nodes the energy counts and the rigid bodies
  const auto skip = skipped_nodes(s);
  for (std::size_t i = 0; i < skip.size(); ++i)
    if (!skip[i]) mass_kg += s.mass()[i];
  for (const auto& b : s.rigid_bodies()) mass_kg += b.mass_kg;
  if (!(mass_kg > 0.0) || !(t_end_s > 0.0)) return 0.0;
  double impulse_Ns = mass_kg * norm(m.controls.gravity_m_s2) * t_end_s;
  for (const auto& l : m.loads)
    impulse_Ns += static_cast<double>(l.nodes.size()) * integral_of_magnitude(l.force, t_end_s);
  return impulse_Ns * impulse_Ns / (2.0 * mass_kg);
}

}  // namespace crashlink::integration
