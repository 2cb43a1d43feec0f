#include "solver/integration/solver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "solver/integration/central_difference.h"
#include "solver/integration/energy_scale.h"

namespace crashlink::integration {

namespace {

using materials::MaterialKind;
using model::ElementKind;

}  // namespace

Solver::Solver(const model::Model& model, std::string domain_name)
    : model_(model), domain_(std::move(domain_name)) {
  model::validate(model_);
  n_ = model_.nodes.count();
}

Solver::~Solver() = default;
Solver::Solver(Solver&&) noexcept = default;

void Solver::assemble_masses() {
  mass_.assign(n_, 0.0);
  inertia_.assign(n_, 0.0);
  const double* x0 = model_.nodes.x0.data();
  for (const auto& p : model_.parts) {
    const auto& mat = model_.materials[static_cast<std::size_t>(p.material)];
    if (p.kind == ElementKind::Hex8)
      elements::hex8_lumped_mass(p, mat, x0, mass_.data());
    else
      elements::shell_lumped_mass(p, mat, x0, mass_.data(), inertia_.data());
  }
}

void Solver::apply_initial_velocities() {
  for (const auto& iv : model_.initial_velocities) {
    const bool spin = iv.angular_velocity_rad_s[0] != 0.0 || iv.angular_velocity_rad_s[1] != 0.0 ||
                      iv.angular_velocity_rad_s[2] != 0.0;
    for (auto c : iv.nodes) {
      const auto i = static_cast<std::size_t>(c);
      const Vec3 v = spin ? iv.at({model_.nodes.x0[3 * i], model_.nodes.x0[3 * i + 1],
                                   model_.nodes.x0[3 * i + 2]})
                          : iv.velocity_m_s;
      for (std::size_t d = 0; d < 3; ++d) v_[3 * i + d] = v[d];
      // a node with rotations turns with the spin (a later translation stops it)
      if (inertia_[i] > 0.0)
        for (std::size_t d = 0; d < 3; ++d) omega_[3 * i + d] = iv.angular_velocity_rad_s[d];
    }
  }
  for (auto& b : bodies_)
    for (std::size_t k = 0; k < b.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(b.nodes[k]);
      const Vec3 r{b.offsets[3 * k], b.offsets[3 * k + 1], b.offsets[3 * k + 2]};
      const Vec3 vi = b.velocity + cross(b.omega, r);
      for (std::size_t d = 0; d < 3; ++d) v_[3 * i + d] = vi[d];
    }
  turn_rigid_nodes();
  prescribed_node_.assign(n_, 0);
  for (const auto& pv : model_.prescribed_velocities) {
    const bool rot = pv.dof >= 3;
    for (auto c : pv.nodes) {
      const std::size_t idx =
          3 * static_cast<std::size_t>(c) + static_cast<std::size_t>(pv.dof % 3);
      if (rigid_node_[static_cast<std::size_t>(c)])
        throw ModelError(
            fmt::format("prescribed velocity '{}': node {} follows a rigid body; "
                        "prescribe the body's motion instead",
                        pv.name, model_.nodes.id[static_cast<std::size_t>(c)]));
      prescribed_.push_back({idx, rot, &pv.velocity});
      prescribed_node_[static_cast<std::size_t>(c)] = 1;
      (rot ? omega_ : v_)[idx] = pv.velocity.at(0.0);
    }
  }
  walls_.clear();
  for (const auto& w : model_.rigid_walls) {
    for (auto c : w.nodes)
      if (rigid_node_[static_cast<std::size_t>(c)])
        throw ModelError(fmt::format(
            "rigid wall '{}': node {} follows a rigid body; a wall stops deformable nodes only "
            "(fix: leave the body's nodes out of the wall's node set)",
            w.name, model_.nodes.id[static_cast<std::size_t>(c)]));
    WallRuntime rw;
    rw.wall = &w;
    rw.reaction_prev.assign(3 * w.nodes.size(), 0.0);
    rw.gap.assign(4 * w.nodes.size(), 0.0);
    walls_.push_back(std::move(rw));
    walls_.back().velocity_m_s = w.velocity_m_s;
  }
  v_prev_ = v_;
  omega_prev_ = omega_;
}

void Solver::initialize() {
  const std::size_t n3 = 3 * n_;
  for (auto* vec : {&x_, &u_, &v_, &v_prev_, &a_, &omega_, &omega_prev_, &alpha_, &f_int_, &f_ext_,
                    &m_int_, &du_, &f_cont_, &f_coup_, &m_coup_, &dtheta_})
    vec->assign(n3, 0.0);
  x_ = model_.nodes.x0;
  const Vec3& gravity = model_.controls.gravity_m_s2;
  external_loads_ =
      gravity[0] != 0.0 || gravity[1] != 0.0 || gravity[2] != 0.0 || !model_.loads.empty();
  coupled_.reset(n_);
  contact_nodes_.reset(n_);
  assemble_masses();
  if (!mass_override_.empty()) {
    if (mass_override_.size() != n_)
      throw ModelError(
          fmt::format("{}: {} mass overrides for {} nodes", domain_, mass_override_.size(), n_));
    for (std::size_t i = 0; i < n_; ++i)
      if (mass_override_[i] > 0.0) mass_[i] = mass_override_[i];
  }
  if (!inertia_override_.empty()) {
    if (inertia_override_.size() != n_)
      throw ModelError(fmt::format("{}: {} inertia overrides for {} nodes", domain_,
                                   inertia_override_.size(), n_));
    for (std::size_t i = 0; i < n_; ++i)
      if (inertia_override_[i] > 0.0) inertia_[i] = inertia_override_[i];
  }
  ghost_.assign(n_, 0);
  for (auto g : ghost_list_) {
    if (g < 0 || static_cast<std::size_t>(g) >= n_)
      throw ModelError(fmt::format("{}: ghost node index {} out of range", domain_, g));
    ghost_[static_cast<std::size_t>(g)] = 1;
  }
  ghost_target_.assign(3 * ghost_list_.size(), 0.0);
  ghost_omega_.assign(3 * ghost_list_.size(), 0.0);
  ghost_u_prev_.assign(3 * ghost_list_.size(), 0.0);
  ghost_reaction_.assign(3 * ghost_list_.size(), 0.0);
  ghost_reaction_moment_.assign(3 * ghost_list_.size(), 0.0);
  parts_.clear();
  for (const auto& p : model_.parts) {
    PartRuntime r;
    if (!is_rigid(model_, p)) {
      if (p.kind == ElementKind::Hex8)
        r.state = elements::make_hex8_state(p);
      else
        r.state = elements::make_shell_state(p);
    }
    parts_.push_back(std::move(r));
  }
  build_rigid_bodies();
  inv_mass_.assign(n_, 0.0);
  inv_inertia_.assign(n_, 0.0);
  for (std::size_t i = 0; i < n_; ++i) {
    if (rigid_node_[i] || ghost_[i]) continue;
    if (mass_[i] > 0.0) inv_mass_[i] = 1.0 / mass_[i];
    if (inertia_[i] > 0.0) inv_inertia_[i] = 1.0 / inertia_[i];
  }
  apply_initial_velocities();
  // The whole model's scale when the decomposition gave one: a domain's own could exceed it (the
  // loads' impulse on a light domain's mass, energy_scale.h pushed_energy_J).
  guard_floor_J_ = kGuardFloorFraction * (model_.controls.model_energy_scale_J > 0.0
                                              ? model_.controls.model_energy_scale_J
                                              : model_energy_scale_J(*this));
  contacts_.clear();
  for (const auto& c : model_.contacts) contacts_.emplace_back(model_, c, mass_.data());
  contact_steps_.assign(contacts_.size(), {});
  contact_block_end_.clear();  // the interfaces' blocks, numbered one after the other
  for (const auto& c : contacts_)
    contact_block_end_.push_back((contact_block_end_.empty() ? 0 : contact_block_end_.back()) +
                                 c.block_count());
  time_s_ = 0.0;
  cycle_ = 0;
  dt_prev_ = 0.0;
  dt_increment_s_ = 0.0;
  increments_everywhere_ = true;  // du_ and dtheta_ are the zeros above
  velocity_moved_ = false;
  // The interior elements of each part: those before its first element on a ghost node, in
  // whole batches.
  interior_end_.assign(model_.parts.size(), 0);
  for (std::size_t p = 0; p < model_.parts.size(); ++p) {
    const auto& part = model_.parts[p];
    const std::size_t ne = part.element_count();
    const auto k = static_cast<std::size_t>(model::nodes_per_element(part.kind));
    std::size_t e = 0;
    while (e < ne &&
           std::none_of(part.connectivity.begin() + static_cast<std::ptrdiff_t>(k * e),
                        part.connectivity.begin() + static_cast<std::ptrdiff_t>(k * e + k),
                        [&](std::int32_t c) { return ghost_[static_cast<std::size_t>(c)] != 0; }))
      ++e;
    interior_end_[p] = e == ne ? ne : e / elements::kElementBatch * elements::kElementBatch;
  }
  set_up_threads();
  const bool record = record_element_steps_;
  record_element_steps_ = record || !contacts_.empty() || model_.controls.global_stable_step;
  compute_forces(0.0);
  record_element_steps_ = record || model_.controls.global_stable_step;
  set_up_global_step();
  set_contact_step_references();
  compute_contact_forces(0.0);
  compute_external_forces(0.0);
  compute_accelerations();
  propose_step();
  dt_min_ = dt_;
  energy_ = EnergyAccount{};
  begun_ = false;
}

void Solver::set_contact_step_references() {
  // Each contact's soft springs are sized with dt_scale x the least stable step of the elements
  // on its nodes at the start (contact_pass.cpp pair_stiffness): a property of the contact's own
  // elements, the same in mono and in whichever domain of a cut model holds the contact.
  // The contact's elements (as for its masses, node_properties.h): those of its master parts
  // and those holding a slave node.
  std::vector<std::uint8_t> mark(n_, 0);
  for (std::size_t ci = 0; ci < contacts_.size(); ++ci) {
    auto& c = contacts_[ci];
    const auto& mc = model_.contacts[ci];
    for (auto i : mc.slave_nodes) mark[static_cast<std::size_t>(i)] = 1;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < parts_.size(); ++p) {
      const auto& steps = parts_[p].element_dt_s;
      if (steps.empty()) continue;
      const auto& part = model_.parts[p];
      const bool master = std::find(mc.master_parts.begin(), mc.master_parts.end(),
                                    static_cast<int>(p)) != mc.master_parts.end();
      const auto k = static_cast<std::size_t>(model::nodes_per_element(part.kind));
      for (std::size_t e = 0; e < steps.size(); ++e) {
        bool mine = master;
        for (std::size_t a = 0; a < k && !mine; ++a)
          mine = mark[static_cast<std::size_t>(part.connectivity[k * e + a])] != 0;
        if (mine) least = std::min(least, steps[e]);
      }
    }
    for (auto i : mc.slave_nodes) mark[static_cast<std::size_t>(i)] = 0;
    if (!std::isfinite(least)) least = dt_stable_;  // rigid on rigid: the domain's step
    if (std::isfinite(least)) c.set_step_reference(model_.controls.dt_scale * least);
  }
}

void Solver::compute_contact_forces(double dt) {
  if (contacts_.empty()) return;
  // f_cont is zero but at the nodes the contacts pushed last time (contact_nodes_)
  for (const auto node : contact_nodes_.nodes())
    for (std::size_t k = 3 * static_cast<std::size_t>(node);
         k < 3 * static_cast<std::size_t>(node) + 3; ++k)
      f_cont_[k] = 0.0;
  contact_nodes_.clear();
  // The penalty springs add to the highest frequency of the nodes they hold: a node of the
  // critical element on a spring of frequency w_c vibrates at up to sqrt(w_e^2 + w_c^2) (the
  // largest eigenvalue of a sum of positive semi-definite stiffnesses is at most the sum of
  // theirs). The step dt = s dt_e (s = controls.dt_scale, w_e dt_e = 2) is stable while
  // (2 s)^2 + (w_c dt)^2 <= 4, i.e. dt <= 2 sqrt(1 - s^2) / w_c = dt_c sqrt(1 - s^2) (dt_c =
  // 2 / w_c, the springs' own critical step): as a stable step before the factor s,
  //   dt_stable <= dt_c sqrt(1 - s^2) / s     (0.48 dt_c at s = 0.9; s taken <= 0.995).
  // A minimum, so that every domain of a cut model bounds its own springs as mono does; a soft
  // spring (k = 0.1 m / dt^2, w_c dt = 0.32) never binds, a stiff one on a light node does: the
  // former bound sqrt(2 m / k) = 1.41 / w_c let a corner node blow up.
  const double sf = std::min(model_.controls.dt_scale, 0.995);  // s -> 1 leaves no room
  const double share = std::sqrt(1.0 - sf * sf) / sf;
  // CPU of the calling thread, and of each worker's run of blocks (not its wait: a worker spins
  // before it sleeps, and that is no contact's cost)
  const double t0 = core::thread_cpu_seconds();
  // Every interface's blocks of slave nodes in one loop of the team, a fixed run of them per
  // thread (so that each block's nodes' friction, side and wake state stay in one core's cache:
  // handed out to whichever thread was free, the blocks, a few microseconds each, cost more
  // than they saved; docs/threads.md), then each interface's forces in order.
  for (auto& c : contacts_) c.begin(x_.data(), v_.data(), dt);
  const auto run_block = [&](std::size_t b) {
    std::size_t k = 0;
    while (b >= contact_block_end_[k]) ++k;
    contacts_[k].block(b - (k == 0 ? 0 : contact_block_end_[k - 1]));
  };
  const std::size_t blocks = contact_block_end_.empty() ? 0 : contact_block_end_.back();
  if (team_ && blocks > 1)
    team_->on_each_thread([&](int t) {
      const auto T = static_cast<std::size_t>(team_->size()), k = static_cast<std::size_t>(t);
      const double c0 = t > 0 ? core::thread_cpu_seconds() : 0.0;
      for (std::size_t b = blocks * k / T; b < blocks * (k + 1) / T; ++b) run_block(b);
      if (t > 0) contact_worker_cpu_[k] += core::thread_cpu_seconds() - c0;
    });
  else
    for (std::size_t b = 0; b < blocks; ++b) run_block(b);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    contact_steps_[k] = contacts_[k].finish(f_cont_.data());
    add_contact_nodes(k);
    contact_cost_.node_cycles += static_cast<std::int64_t>(contacts_[k].slave_node_count());
    const double bound = share * contact_steps_[k].dt_stable_s;
    if (bound < dt_stable_) {
      dt_stable_ = bound;
      global_.binds = false;
      critical_part_ = model_.parts.size();  // "no element": reported as the contact
      critical_local_ = -1 - static_cast<std::int64_t>(k);
    }
  }
  double workers = 0.0;
  for (auto& c : contact_worker_cpu_) {
    workers += c;
    c = 0.0;
  }
  contact_cost_.seconds += core::thread_cpu_seconds() - t0 + workers;
}

void Solver::compute_external_forces(double t) {
  if (!external_loads_) return;  // f_ext stays the zeros initialize() made
  std::fill(f_ext_.begin(), f_ext_.end(), 0.0);
  const Vec3& g = model_.controls.gravity_m_s2;
  if (g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0)
    for (std::size_t i = 0; i < n_; ++i) {
      // a rigid body's weight is M g, added in gather_rigid_load; a ghost's mass (and weight)
      // belongs to its owner domain
      if (rigid_node_[i] || ghost_[i]) continue;
      for (std::size_t d = 0; d < 3; ++d) f_ext_[3 * i + d] += mass_[i] * g[d];
    }
  for (const auto& load : model_.loads) {
    const double f = load.force.at(t);
    for (auto c : load.nodes)
      f_ext_[3 * static_cast<std::size_t>(c) + static_cast<std::size_t>(load.dof)] += f;
  }
}

GuardContext Solver::guard_context() const {
  return {cycle_, time_s_, dt_, domain_};
}

void Solver::begin_cycle() {
  const double dt_mid = mid_step(dt_prev_, dt_);  // dt^{n-1/2}, [2]
  // Without prescribed velocities and after the start, one pass does it all: velocities,
  // held dofs and the nodes' kinetic energy (velocity_pass).
  const bool one_pass = cycle_ > 0 && prescribed_.empty() && walls_.empty();
  // The last displacement update's velocities move to v_prev_ (du_at reads them there).
  CRASHLINK_ASSERT(!velocity_moved_ || increments_everywhere_);
  velocity_moved_ = true;
  if (one_pass) {
    const double ke_nodes = velocity_pass(dt_mid);
    update_rigid_bodies(dt_mid);
    turn_rigid_nodes();
    energy_.kinetic_J = kinetic_energy_from(ke_nodes);
  } else {
    // v^{n-1/2} kept for the kinetic energy's product form, then v^{n+1/2} = v^{n-1/2} +
    // dt^{n-1/2} a^n ([2]), in one pass per field.
    advance_velocity(v_.data(), v_prev_.data(), a_.data(), dt_mid, v_.size());
    advance_velocity(omega_.data(), omega_prev_.data(), alpha_.data(), dt_mid, omega_.size());
    update_rigid_bodies(dt_mid);
    turn_rigid_nodes();
  }
  if (cycle_ == 0) {
    // The start v^{1/2} = v^0 + dt^0/2 a^0 is a half step; the kinetic energy's product form
    // needs the full-step partner v^{-1/2} = v^0 - dt^0/2 a^0 = 2 v^0 - v^{1/2} so that
    // KE^0 + IE^0 balances the trapezoid work exactly (docs/energy-balance.md).
    for (std::size_t i = 0; i < v_.size(); ++i) {
      v_prev_[i] = 2.0 * v_prev_[i] - v_[i];
      omega_prev_[i] = 2.0 * omega_prev_[i] - omega_[i];
    }
    for (auto& b : bodies_) {
      b.velocity_prev = 2.0 * b.velocity_prev - b.velocity;
      b.omega_prev = 2.0 * b.omega_prev - b.omega;
    }
  }
  if (!one_pass) zero_held(model_.fixed, v_.data(), omega_.data(), 0, n_);
  // Prescribed velocities and the work of their reactions R^n = m a^n - (f_ext - f_int)^n,
  // trapezoid rule over [t^{n-1}, t^n] (energy.h).
  const double t_mid = time_s_ + 0.5 * dt_;
  for (auto& p : prescribed_) {
    auto& vel = p.rotational ? omega_ : v_;
    const auto& vel_prev = p.rotational ? omega_prev_ : v_prev_;
    vel[p.index] = p.curve->at(t_mid);
    const std::size_t node = p.index / 3;
    const double m = p.rotational ? inertia_[node] : mass_[node];
    const double f_net =
        p.rotational ? m_coup_[p.index] - m_int_[p.index]
                     : f_ext_[p.index] + f_cont_[p.index] + f_coup_[p.index] - f_int_[p.index];
    // M (v^{n+1/2} - v^{n-1/2}) = dt (F + R), with dt the step that pairs the two velocities:
    // dt^{n-1/2}, or the full dt^0 at the first cycle (see above).
    const double dt_pair = cycle_ == 0 ? dt_ : dt_mid;
    const double reaction = m * (vel[p.index] - vel_prev[p.index]) / dt_pair - f_net;
    const double increment = p.rotational ? dt_prev_ * vel_prev[p.index] : du_[p.index];
    if (cycle_ > 0) energy_.external_work_J += 0.5 * (p.reaction_prev + reaction) * increment;
    p.reaction_prev = reaction;
  }
  if (!walls_.empty()) apply_rigid_walls(cycle_ == 0 ? dt_ : dt_mid);
  if (!one_pass) energy_.kinetic_J = kinetic_energy();
  const GuardContext ctx = guard_context();
  if (!std::isfinite(energy_.kinetic_J)) check_finite_velocities(model_, v_.data(), ctx);
  if (cycle_ == 0) energy_.initial_total_J = energy_.total_J();
  energy_.update_reference();
  // Energy the contacts created counts as error (contact_creation.h): each domain's solver
  // guards the interfaces it computes.
  check_energy_balance(model_, energy_, {model_.controls.energy_tolerance, guard_floor_J_},
                       v_.data(), ctx, contact_creation(contact_steps_));
  begun_ = true;
}

void Solver::end_cycle() {
  end_cycle_forces();
  end_cycle_accelerations();
}

void Solver::end_cycle_forces() {
  end_cycle_positions();
  end_cycle_compute();
}

void Solver::end_cycle_positions() {
  CRASHLINK_ASSERT(begun_);
  CRASHLINK_ASSERT(!positions_done_);
  const double dt = dt_;
  // The ghosts' u^n and reaction at t^n, for apply_ghost_motion() once their motion is known.
  for (std::size_t k = 0; k < ghost_list_.size(); ++k)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t i = 3 * static_cast<std::size_t>(ghost_list_[k]) + d;
      ghost_u_prev_[3 * k + d] = u_[i];
      ghost_reaction_[3 * k + d] = ghost_reaction(i);
      ghost_reaction_moment_[3 * k + d] = ghost_reaction_moment(i);
    }
  // [2] for every node; the ghosts' values are provisional (apply_ghost_motion).
  advance_positions(dt);
  for (auto& rw : walls_) rw.travel_m += dt * rw.velocity_m_s;  // a moving wall's plane
  const Vec3& g = model_.controls.gravity_m_s2;
  double rigid_gravity_work = 0.0;
  for (auto& b : bodies_) {
    if (b.failed) continue;
    move_rigid_body(b, dt, model_.nodes.x0.data(), u_.data(), v_.data());
    for (auto c : b.nodes)
      for (std::size_t d = 0; d < 3; ++d) {
        const std::size_t k = 3 * static_cast<std::size_t>(c) + d;
        du_[k] = dt * v_[k];
      }
    rigid_gravity_work += b.mass_kg * dot(g, dt * b.velocity);
  }
  time_s_ += dt;
  // Every work term by the trapezoid rule 1/2 (F^n + F^{n+1}) . (u^{n+1} - u^n) (energy.h):
  // first the F^n halves, then the forces at t^{n+1}, then their halves. Here: x^{n+1} where the
  // displacement pass left it, the F^n halves, and the coupling loads of t^n cleared.
  const StepWork w = positions_and_work();
  // Until apply_ghost_motion, a ghost's position and velocity are NaN: a force computed from them
  // (an element taken for interior that is not) is not finite, and the guard stops the run.
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  for (const auto gh : ghost_list_)
    for (std::size_t d = 0; d < 3; ++d) {
      x_[3 * static_cast<std::size_t>(gh) + d] = kUnknown;
      v_[3 * static_cast<std::size_t>(gh) + d] = kUnknown;
    }
  energy_.external_work_J += 0.5 * w.external + rigid_gravity_work;
  // Contact energy = minus the work of the contact forces (penalty spring energy + friction
  // dissipation).
  if (!contacts_.empty()) energy_.contact_J -= 0.5 * w.contact;
  energy_.coupling_work_J += 0.5 * w.coupling + 0.5 * w.coupling_moment;
  positions_done_ = true;
}

void Solver::end_cycle_interior_forces() {
  CRASHLINK_ASSERT(positions_done_);
  CRASHLINK_ASSERT(!interior_done_);
  compute_forces(dt_, ElementSpan::Interior);
  interior_done_ = true;
}

void Solver::end_cycle_compute() {
  CRASHLINK_ASSERT(positions_done_);
  const double dt = dt_;
  if (!interior_done_) compute_forces(dt, ElementSpan::Interior);
  apply_ghost_motion();
  compute_forces(dt, ElementSpan::Rim);
  apply_global_step();
  positions_done_ = false;
  interior_done_ = false;
  compute_contact_forces(dt);
  compute_external_forces(time_s_);
  if (external_loads_)
    energy_.external_work_J += 0.5 * sum_over_tiles([&](std::size_t i0, std::size_t i1) {
                                 return external_increment_work(i0, i1);
                               });
  if (!contacts_.empty())
    energy_.contact_J -= 0.5 * increment_dot(contact_nodes_.nodes(), f_cont_.data());
  energy_.coupling_work_J += ghost_reaction_work(0.5);
}

void Solver::end_cycle_accelerations() {
  compute_accelerations();
  dt_prev_ = dt_;
  ++cycle_;
  propose_step();
  dt_min_ = std::min(dt_min_, dt_);
  begun_ = false;
}

}  // namespace crashlink::integration
