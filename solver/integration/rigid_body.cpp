#include "solver/integration/rigid_body.h"

namespace crashlink::integration {

void gather_rigid_load(RigidBodyState& b, const NodalLoads& loads, const double* x,
                       const Vec3& gravity) {
  Vec3 f = b.mass_kg * gravity;
  Vec3 t{};
  const auto net = [&](std::size_t k) {
    return loads.f_ext[k] + loads.f_cont[k] + loads.f_coup[k] - loads.f_int[k];
  };
  for (std::int32_t node : b.nodes) {
    const auto i = static_cast<std::size_t>(node);
    const Vec3 fi{net(3 * i), net(3 * i + 1), net(3 * i + 2)};
    const Vec3 r = Vec3{x[3 * i], x[3 * i + 1], x[3 * i + 2]} - b.centre;
    f = f + fi;
    t = t + cross(r, fi);
  }
  for (std::int32_t node : b.turning) {
    const auto i = static_cast<std::size_t>(node);
    t = t + Vec3{loads.m_ext[3 * i] - loads.m_int[3 * i],
                 loads.m_ext[3 * i + 1] - loads.m_int[3 * i + 1],
                 loads.m_ext[3 * i + 2] - loads.m_int[3 * i + 2]};
  }
  b.force = f;
  b.torque = t;
}

Mat3 spatial_inertia(const RigidBodyState& b) {
  return mul(mul(b.rotation, b.inertia_body), transpose(b.rotation));
}

void update_rigid_momenta(RigidBodyState& b, double dt_mid) {
  b.velocity_prev = b.velocity;
  b.omega_prev = b.omega;
  b.velocity = b.velocity + (dt_mid / b.mass_kg) * b.force;
  b.angular_momentum = b.angular_momentum + dt_mid * b.torque;
  const Mat3 j_inv = mul(mul(b.rotation, b.inertia_body_inv), transpose(b.rotation));
  b.omega = mul(j_inv, b.angular_momentum);
}

void move_rigid_body(RigidBodyState& b, double dt, const double* x0, double* u, double* v) {
  const Vec3 c_old = b.centre;
  const Mat3 r_old = b.rotation;
  b.centre = b.centre + dt * b.velocity;
  b.rotation = mul(rotation_from_vector(dt * b.omega), b.rotation);
  const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  for (std::size_t k = 0; k < b.nodes.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(b.nodes[k]);
    const Vec3 X{b.offsets[3 * k], b.offsets[3 * k + 1], b.offsets[3 * k + 2]};
    const Vec3 x_new = b.centre + mul(b.rotation, X);
    const Vec3 x_old = c_old + mul(r_old, X);
    for (std::size_t d = 0; d < 3; ++d) {
      u[3 * i + d] = x_new[d] - x0[3 * i + d];
      v[3 * i + d] = dt > 0.0 ? (x_new[d] - x_old[d]) * inv_dt : b.velocity[d];
    }
  }
}

Vec3 rigid_point_acceleration(const RigidBodyState& b, const Vec3& x) {
  const Mat3 j = spatial_inertia(b);
  const Mat3 j_inv = mul(mul(b.rotation, b.inertia_body_inv), transpose(b.rotation));
  const Vec3 w = b.omega;
  const Vec3 alpha = mul(j_inv, b.torque - cross(w, mul(j, w)));
  const Vec3 r = x - b.centre;
  return (1.0 / b.mass_kg) * b.force + cross(alpha, r) + cross(w, cross(w, r));
}

double rigid_kinetic_energy(const RigidBodyState& b) {
  const Mat3 j = spatial_inertia(b);
  return 0.5 * (b.mass_kg * dot(b.velocity_prev, b.velocity) + dot(b.omega_prev, mul(j, b.omega)));
}

}  // namespace crashlink::integration
