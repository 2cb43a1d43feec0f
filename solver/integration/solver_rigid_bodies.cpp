// The solver's rigid bodies (solver.h, rigid_body.h): built from rigid parts and extra nodes,
// their turning shell nodes, and spot welds letting go of their nodes.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/errors.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

void Solver::build_rigid_bodies() {
  rigid_node_.assign(n_, 0);
  body_of_node_.assign(n_, -1);
  std::vector<int> part_body(model_.parts.size(), -1);
  for (std::size_t b = 0; b < model_.rigid_bodies.size(); ++b) {
    const auto& rb = model_.rigid_bodies[b];
    RigidBodyState s;
    // each node follows one body: body_of_node_ names the owner
    const auto take = [&](std::int32_t c) {
      const auto i = static_cast<std::size_t>(c);
      if (rigid_node_[i] == 1) {
        if (body_of_node_[i] != static_cast<int>(b))
          throw ModelError(fmt::format(
              "node {} belongs to rigid bodies '{}' and '{}'; merge them into one body",
              model_.nodes.id[i],
              model_.rigid_bodies[static_cast<std::size_t>(body_of_node_[i])].name, rb.name));
        return false;
      }
      rigid_node_[i] = 1;
      body_of_node_[i] = static_cast<int>(b);
      s.nodes.push_back(c);
      return true;
    };
    for (int pi : rb.parts) {
      part_body[static_cast<std::size_t>(pi)] = static_cast<int>(b);
      for (auto c : model_.parts[static_cast<std::size_t>(pi)].connectivity) (void)take(c);
    }
    // Extra nodes (a nodal rigid body, *CONSTRAINED_EXTRA_NODES): those of deformable shells
    // turn with the body.
    for (auto c : rb.nodes) {
      const auto i = static_cast<std::size_t>(c);
      if (!model_.fixed.empty() && model_.fixed[i] != 0)
        throw ModelError(fmt::format(
            "node {} of rigid body '{}' is held by a boundary condition, which the body's motion "
            "would override; fix: leave it out of the held nodes (or of the body)",
            model_.nodes.id[i], rb.name));
      if (take(c) && inertia_[i] > 0.0) s.turning.push_back(c);
    }
    double m_sum = 0.0;
    Vec3 mx{};
    for (auto c : s.nodes) {
      const auto i = static_cast<std::size_t>(c);
      m_sum += mass_[i];
      mx = mx + mass_[i] * Vec3{model_.nodes.x0[3 * i], model_.nodes.x0[3 * i + 1],
                                model_.nodes.x0[3 * i + 2]};
    }
    if (!(m_sum > 0.0) && !(rb.mass_kg > 0.0))
      throw ModelError(
          fmt::format("rigid body '{}' has no mass: give its parts a density or set "
                      "its mass",
                      rb.name));
    s.mass_kg = rb.mass_kg > 0.0 ? rb.mass_kg : m_sum;
    const double scale = m_sum > 0.0 ? s.mass_kg / m_sum : 0.0;  // given mass: scale the nodes
    s.centre0 = rb.centre_given ? rb.centre_m : (1.0 / m_sum) * mx;
    s.centre = s.centre0;
    Mat3 j{};
    s.offsets.resize(3 * s.nodes.size());
    for (std::size_t k = 0; k < s.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(s.nodes[k]);
      const Vec3 r =
          Vec3{model_.nodes.x0[3 * i], model_.nodes.x0[3 * i + 1], model_.nodes.x0[3 * i + 2]} -
          s.centre0;
      for (std::size_t d = 0; d < 3; ++d) s.offsets[3 * k + d] = r[d];
      const double mi = scale * mass_[i];
      for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t c = 0; c < 3; ++c)
          j[a][c] += mi * ((a == c ? dot(r, r) : 0.0) - r[a] * r[c]);
    }
    // the turning nodes' own rotational inertias (isotropic) add to the body's
    for (auto c : s.turning)
      for (std::size_t a = 0; a < 3; ++a) j[a][a] += scale * inertia_[static_cast<std::size_t>(c)];
    if (!rb.inertia_given) {
      // Nodes on one line without rotational inertia (a spot weld of two solids' nodes): no
      // inertia about the line. A hundredth of the mean moment about every axis makes the
      // spin about it finite (it is not defined by such nodes: any finite value serves).
      const double mean = (j[0][0] + j[1][1] + j[2][2]) / 3.0;
      const double det_j = determinant(j);
      if (mean > 0.0 && !(det_j > 1e-9 * mean * mean * mean))
        for (std::size_t a = 0; a < 3; ++a) j[a][a] += 0.01 * mean;
    }
    s.inertia_body = rb.inertia_given ? rb.inertia_kg_m2 : j;
    const double det = determinant(s.inertia_body);
    if (!(det > 0.0))
      throw ModelError(
          fmt::format("rigid body '{}': inertia tensor is singular (det {:.3e}); give "
                      "its inertia explicitly",
                      rb.name, det));
    s.inertia_body_inv = inverse(s.inertia_body);
    s.breakable = rb.failure.any();
    // the centre's velocity (rb.velocity_m_s is its point p's with velocity_at_point)
    s.velocity = rb.velocity_m_s;
    if (rb.velocity_at_point)
      s.velocity = s.velocity + cross(rb.angular_velocity_rad_s, s.centre0 - rb.velocity_point_m);
    s.velocity_prev = s.velocity;
    s.omega = rb.angular_velocity_rad_s;
    s.omega_prev = rb.angular_velocity_rad_s;
    s.angular_momentum = mul(s.inertia_body, rb.angular_velocity_rad_s);
    bodies_.push_back(std::move(s));
  }
  build_body_motions();
  for (std::size_t p = 0; p < model_.parts.size(); ++p)
    if (is_rigid(model_, model_.parts[p]) && part_body[p] < 0)
      throw ModelError(
          fmt::format("part '{}' is rigid but belongs to no rigid body; list it under "
                      "rigid_bodies",
                      model_.parts[p].name));
}

void Solver::build_body_motions() {
  body_motions_.clear();
  std::vector<std::uint8_t> taken(bodies_.size(), 0);
  const auto add = [&](std::size_t k, int dof, const model::Curve* curve, const std::string& by) {
    const auto bit = static_cast<std::uint8_t>(1u << dof);
    if (taken[k] & bit)
      throw ModelError(fmt::format(
          "rigid body '{}': its {} {} is held or prescribed twice (again by {}); fix: keep one",
          model_.rigid_bodies[k].name, dof < 3 ? "velocity along" : "rotation about",
          "xyz"[dof % 3], by));
    taken[k] |= bit;
    body_motions_.push_back({k, dof, curve});
  };
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    for (int dof = 0; dof < 6; ++dof)
      if (model_.rigid_bodies[k].fixed & (1u << dof)) add(k, dof, nullptr, "its own constraints");
  for (const auto& pv : model_.prescribed_velocities)
    if (pv.rigid_body >= 0)
      add(static_cast<std::size_t>(pv.rigid_body), pv.dof, &pv.velocity,
          fmt::format("prescribed motion '{}'", pv.name));
  body_held_.assign(bodies_.size(), 0);
  // the motions' values at t = 0 replace the body's initial velocity on their dofs
  for (const auto& bm : body_motions_) {
    body_held_[bm.body] = 1;
    auto& b = bodies_[bm.body];
    const double v0 = bm.curve ? bm.curve->at(0.0) : 0.0;
    auto& target = bm.dof < 3 ? b.velocity : b.omega;
    target[static_cast<std::size_t>(bm.dof % 3)] = v0;
    (bm.dof < 3 ? b.velocity_prev : b.omega_prev) = target;
    if (bm.dof >= 3) b.angular_momentum = mul(b.inertia_body, b.omega);
  }
}

void Solver::update_rigid_bodies(double dt_mid) {
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    if (bodies_[k].failed) continue;
    update_rigid_momenta(bodies_[k], dt_mid);
    if (body_held_[k]) constrain_rigid_body(k, dt_mid);
  }
}

/// A body's translations are independent: the held or prescribed centre velocity v_d replaces
/// the free one, the reaction R_d = M (v_d - v_free,d) / dt_mid (the impulse over the momentum
/// update). Its rotations are coupled through the spatial inertia J = R J_b R^T: the reaction
/// moment acts about the constrained axes s only, L = L_free + sum_s lambda_s e_s, with lambda
/// from (J^-1)_SS lambda = omega_target,S - omega_free,S (a 1x1 to 3x3 system), so that the
/// free axes keep their dynamics. Work: 1/2 (R^{n-1} + R^n) (c^n - c^{n-1})_d, or the rotation
/// dt^{n-1} omega^{n-1/2}_s, as a node's prescribed velocity (energy.h).
void Solver::constrain_rigid_body(std::size_t k, double dt_mid) {
  auto& b = bodies_[k];
  const double t_mid = time_s_ + 0.5 * dt_;
  const Mat3 j_inv = mul(mul(b.rotation, b.inertia_body_inv), transpose(b.rotation));
  const Vec3 omega_free = b.omega;
  std::array<std::size_t, 3> axis{};
  std::array<double, 3> rhs{};
  std::array<BodyMotion*, 3> rot{};
  std::size_t ns = 0;
  for (auto& bm : body_motions_) {
    if (bm.body != k) continue;
    const double target = bm.curve ? bm.curve->at(t_mid) : 0.0;
    const auto d = static_cast<std::size_t>(bm.dof % 3);
    if (bm.dof < 3) {
      const double reaction = b.mass_kg * (target - b.velocity[d]) / dt_mid;
      b.velocity[d] = target;
      b.force[d] += reaction;  // F^n with the reaction: the probes' acceleration (F/M) at t^n
      if (cycle_ > 0)
        energy_.external_work_J +=
            0.5 * (bm.reaction_prev + reaction) * dt_prev_ * b.velocity_prev[d];
      bm.reaction_prev = reaction;
    } else {
      axis[ns] = d;
      rhs[ns] = target - omega_free[d];
      rot[ns++] = &bm;
    }
  }
  if (ns == 0) return;
  // (J^-1)_SS lambda = rhs by Gaussian elimination with partial pivoting (SPD: no pivot needed,
  // kept for safety)
  double a[3][4] = {};
  for (std::size_t r = 0; r < ns; ++r) {
    for (std::size_t c = 0; c < ns; ++c) a[r][c] = j_inv[axis[r]][axis[c]];
    a[r][3] = rhs[r];
  }
  for (std::size_t c = 0; c < ns; ++c) {
    std::size_t piv = c;
    for (std::size_t r = c + 1; r < ns; ++r)
      if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
    for (std::size_t q = 0; q < 4; ++q) std::swap(a[c][q], a[piv][q]);
    for (std::size_t r = c + 1; r < ns; ++r) {
      const double f = a[r][c] / a[c][c];
      for (std::size_t q = c; q < 4; ++q) a[r][q] -= f * a[c][q];
    }
  }
  std::array<double, 3> lambda{};
  for (std::size_t r = ns; r-- > 0;) {
    double x = a[r][3];
    for (std::size_t c = r + 1; c < ns; ++c) x -= a[r][c] * lambda[c];
    lambda[r] = x / a[r][r];
  }
  for (std::size_t r = 0; r < ns; ++r) b.angular_momentum[axis[r]] += lambda[r];
  b.omega = mul(j_inv, b.angular_momentum);
  for (std::size_t r = 0; r < ns; ++r) {
    const double reaction = lambda[r] / dt_mid;
    b.torque[axis[r]] += reaction;  // T^n with the reaction moment (rigid_point_acceleration)
    if (cycle_ > 0)
      energy_.external_work_J +=
          0.5 * (rot[r]->reaction_prev + reaction) * dt_prev_ * b.omega_prev[axis[r]];
    rot[r]->reaction_prev = reaction;
  }
}

void Solver::check_spot_welds() {
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    auto& b = bodies_[k];
    if (!b.breakable || b.failed) continue;
    const auto& f = model_.rigid_bodies[k].failure;
    // The force the weld applies to node 2: R_2 = m_2 a_2 - (f_ext + f_cont + f_coup - f_int + m_2
    // g)_2, a_2 the rigid motion's acceleration at node 2 (rigid_point_acceleration). The weld
    // pulls node 2 back toward node 1 when the sheets are pulled apart: its tension is f_n = -R_2 .
    // axis, axis from node 1 to node 2 (LS-DYNA's SN acts in tension only); f_s the rest of R_2.
    const auto i1 = static_cast<std::size_t>(b.nodes[0]), i2 = static_cast<std::size_t>(b.nodes[1]);
    const Vec3 x1{x_[3 * i1], x_[3 * i1 + 1], x_[3 * i1 + 2]};
    const Vec3 x2{x_[3 * i2], x_[3 * i2 + 1], x_[3 * i2 + 2]};
    const Vec3 a2 = rigid_point_acceleration(b, x2);
    const double m2 = (b.mass_kg > 0.0 ? b.mass_kg / (mass_[i1] + mass_[i2]) : 1.0) * mass_[i2];
    Vec3 load = m2 * model_.controls.gravity_m_s2;  // its weight: in the body's M g
    for (std::size_t d = 0; d < 3; ++d) load[d] += driving_load(3 * i2 + d) - f_int_[3 * i2 + d];
    const Vec3 reaction = m2 * a2 - load;
    const Vec3 axis = (1.0 / norm(x2 - x1)) * (x2 - x1);
    const double fn = -dot(reaction, axis);
    const double fs = norm(reaction + fn * axis);
    double crit = 0.0;
    if (f.normal_N > 0.0) crit += std::pow(std::max(fn, 0.0) / f.normal_N, f.exp_n);
    if (f.shear_N > 0.0) crit += std::pow(fs / f.shear_N, f.exp_m);
    const bool timed = f.time_s > 0.0 && time_s_ >= f.time_s;
    if (crit < 1.0 && !timed) continue;
    release_body(k);
    weld_failures_.push_back({model_.rigid_bodies[k].name, time_s_, fn, fs});
  }
}

void Solver::release_body(std::size_t k, bool accelerate) {
  auto& b = bodies_[k];
  b.failed = 1;
  for (auto c : b.nodes) {
    const auto i = static_cast<std::size_t>(c);
    rigid_node_[i] = 0;
    if (!ghost_[i]) {
      inv_mass_[i] = mass_[i] > 0.0 ? 1.0 / mass_[i] : 0.0;
      inv_inertia_[i] = inertia_[i] > 0.0 ? 1.0 / inertia_[i] : 0.0;
    }
    // its own acceleration at t^n, the body's no longer
    for (std::size_t d = 0; accelerate && d < 3; ++d) {
      a_[3 * i + d] = inv_mass_[i] * (driving_load(3 * i + d) - f_int_[3 * i + d]);
      alpha_[3 * i + d] = inv_inertia_[i] * (m_coup_[3 * i + d] - m_int_[3 * i + d]);
    }
  }
}

void Solver::turn_rigid_nodes() {
  for (const auto& b : bodies_)
    for (auto c : b.failed ? std::vector<std::int32_t>{} : b.turning)
      for (std::size_t d = 0; d < 3; ++d) omega_[3 * static_cast<std::size_t>(c) + d] = b.omega[d];
}

}  // namespace crashlink::integration
