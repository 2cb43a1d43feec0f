#pragma once
// Rigid bodies: a set of nodes that follow one body's motion (the headform is one).
// State at half steps like the nodes ([2] of Bourel 2005 applied to the body's momenta):
//   p^{n+1/2} = p^{n-1/2} + dt^{n-1/2} F^n,   L^{n+1/2} = L^{n-1/2} + dt^{n-1/2} T^n
// with the spatial angular momentum L as the primary variable, so that with no torque L is
// constant to round-off; omega^{n+1/2} = R^n J^{-1} R^nT L^{n+1/2}; c^{n+1} = c^n + dt^n v^{n+1/2};
// R^{n+1} = exp(dt^n [omega^{n+1/2}]x) R^n (Rodrigues); node positions x_i = c + R X_i.
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace crashlink::integration {

/// A spot weld that let go: its name, when, and the tension and shear it then carried.
struct WeldFailure {
  std::string name;
  double time_s = 0.0;
  double normal_N = 0.0, shear_N = 0.0;
};

struct RigidBodyState {
  std::vector<std::int32_t> nodes;  ///< node indices that follow the body
  std::vector<double> offsets;      ///< [3k] X_i = x0_i - c0, body frame [m]
  /// Extra nodes of deformable shells (model::RigidBody::nodes with a rotational inertia): their
  /// rotations follow the body (omega_i = omega), their moments enter its torque and their
  /// rotational inertias its inertia.
  std::vector<std::int32_t> turning;
  double mass_kg = 0.0;
  Mat3 inertia_body{};  ///< J about the centre, body frame (= spatial at t0) [kg m^2]
  Mat3 inertia_body_inv{};
  Vec3 centre0{};               ///< c at t0 [m]
  Vec3 centre{};                ///< c^n [m]
  Vec3 velocity{};              ///< v_c^{n+1/2} (after the velocity update) [m/s]
  Vec3 velocity_prev{};         ///< v_c^{n-1/2} [m/s]
  Vec3 angular_momentum{};      ///< L^{n+1/2}, spatial [kg m^2/s]
  Vec3 omega{};                 ///< omega^{n+1/2}, spatial [rad/s]
  Vec3 omega_prev{};            ///< omega^{n-1/2} [rad/s]
  Mat3 rotation = identity3();  ///< R^n body -> spatial
  Vec3 force{};                 ///< F^n total force on the body [N]
  Vec3 torque{};                ///< T^n about c^n [N m]
  bool breakable = false;       ///< a spot weld (model::RigidBody::Failure)
  std::uint8_t failed = 0;      ///< 1: let go of its nodes (they move on their own)
};

/// The nodal loads on a body: the driving load f_ext + f_cont + f_coup, f_int, and the moments
/// m_ext and m_int ([3n] each, N and N m).
struct NodalLoads {
  const double *f_ext, *f_cont, *f_coup, *f_int, *m_ext, *m_int;
};

/// Sums the nodal forces f_ext + f_cont + f_coup - f_int of the body's nodes and the body force
/// mass*gravity into F^n and T^n (about c^n; x = current node coordinates [3n]), and the moments
/// m_ext - m_int of its turning nodes into T^n.
void gather_rigid_load(RigidBodyState& b, const NodalLoads& loads, const double* x,
                       const Vec3& gravity);

/// Momentum update to n+1/2 with dt^{n-1/2}; omega from L with the current orientation.
void update_rigid_momenta(RigidBodyState& b, double dt_mid);

/// Moves the body by dt^n and writes its nodes' displacement u = x - x0 and mid-step velocity
/// v = (x^{n+1} - x^n)/dt^n (so that u and v stay consistent for attached elements).
void move_rigid_body(RigidBodyState& b, double dt, const double* x0, double* u, double* v);

/// The acceleration of the body's material point at x (spatial) at t^n: F/M + alpha x r +
/// omega x (omega x r), r = x - c, alpha from Euler's equations J alpha = T - omega x J omega
/// (F^n, T^n gathered; omega^{n-1/2}, the latest known).
Vec3 rigid_point_acceleration(const RigidBodyState& b, const Vec3& x);

/// Kinetic energy 1/2 (M v^{n-1/2}.v^{n+1/2} + omega^{n-1/2}.J omega^{n+1/2}) in the
/// spatial frame (the same product form as the nodes' kinetic energy, see energy.h).
double rigid_kinetic_energy(const RigidBodyState& b);

/// Spatial inertia R J R^T [kg m^2].
Mat3 spatial_inertia(const RigidBodyState& b);

}  // namespace crashlink::integration
