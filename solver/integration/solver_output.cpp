// What the solver reports (solver.h): nodal velocities at t^n, probes, element output, the model's
// mass.
#include "solver/integration/solver.h"

namespace crashlink::integration {

Vec3 Solver::node_velocity(std::size_t i) const {
  return {0.5 * (v_prev_[3 * i] + v_[3 * i]), 0.5 * (v_prev_[3 * i + 1] + v_[3 * i + 1]),
          0.5 * (v_prev_[3 * i + 2] + v_[3 * i + 2])};
}

ProbeValue Solver::probe(const model::Probe& p) const {
  ProbeValue r;
  const auto i = static_cast<std::size_t>(p.index);
  if (p.kind == model::Probe::Kind::Node) {
    r.displacement_m = {u_[3 * i], u_[3 * i + 1], u_[3 * i + 2]};
    r.velocity_m_s = node_velocity(i);
    r.acceleration_m_s2 = {a_[3 * i], a_[3 * i + 1], a_[3 * i + 2]};
    // a node that follows a body: the body's acceleration there (an accelerometer node tied by a
    // nodal rigid body)
    if (rigid_node_[i] && body_of_node_[i] >= 0 &&
        !bodies_[static_cast<std::size_t>(body_of_node_[i])].failed)
      r.acceleration_m_s2 =
          rigid_point_acceleration(bodies_[static_cast<std::size_t>(body_of_node_[i])],
                                   {x_[3 * i], x_[3 * i + 1], x_[3 * i + 2]});
  } else {
    const auto& b = bodies_[i];
    r.displacement_m = b.centre - b.centre0;
    r.velocity_m_s = 0.5 * (b.velocity_prev + b.velocity);
    r.acceleration_m_s2 = (1.0 / b.mass_kg) * b.force;
  }
  return r;
}

void Solver::element_output(std::size_t p, const elements::ElementOutput& out) const {
  const auto& part = model_.parts[p];
  if (const auto* hs = std::get_if<elements::Hex8State>(&parts_[p].state)) {
    elements::hex8_element_output(part, *hs, out);
  } else if (const auto* ss = std::get_if<elements::ShellState>(&parts_[p].state)) {
    elements::shell_element_output(part, *ss, out);
  } else {
    const std::size_t ne = part.element_count();
    if (out.von_mises_Pa) std::fill(out.von_mises_Pa, out.von_mises_Pa + ne, 0.0);
    if (out.eps_p) std::fill(out.eps_p, out.eps_p + ne, 0.0);
    if (out.stress_Pa) std::fill(out.stress_Pa, out.stress_Pa + 6 * ne, 0.0);
  }
}

double Solver::total_mass_kg() const {
  double m = 0.0;
  for (std::size_t i = 0; i < n_; ++i)
    if (!rigid_node_[i] && !ghost_[i]) m += mass_[i];
  for (const auto& b : bodies_)
    if (!b.failed) m += b.mass_kg;
  return m;
}

}  // namespace crashlink::integration
