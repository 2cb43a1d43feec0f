// The solver's coupling hooks (solver.h "coupling hooks"): summed interface masses and inertias,
// ghost nodes whose motion another domain prescribes (the `layer` scheme's J on the fine side, and
// their reaction work), coupling forces and moments with their work, the `paper` scheme's
// corrected accelerations, and the coarse side's prediction of its next positions.
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "solver/integration/central_difference.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

double Solver::ghost_reaction_work(double weight) const {
  double w = 0.0;
  for (auto g : ghost_list_)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(g) + d;
      w += ghost_reaction(k) * du_[k] + ghost_reaction_moment(k) * dtheta_[k];
    }
  return weight * w;
}

void Solver::apply_ghost_motion() {
  const double dt = dt_;
  if (!ghost_list_.empty() && !ghost_target_set_)
    throw ModelError(
        fmt::format("{}: cycle {}: the ghost nodes' displacement at t^(n+1) was not "
                    "given (set_ghost_displacement before end_cycle_compute)",
                    domain_, cycle_));
  const double* x0 = model_.nodes.x0.data();
  double ext = 0.0, cont = 0.0, ghost_work = 0.0;
  for (std::size_t k = 0; k < ghost_list_.size(); ++k)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t i = 3 * static_cast<std::size_t>(ghost_list_[k]) + d;
      const double target = ghost_target_[3 * k + d];
      const double du = target - ghost_u_prev_[3 * k + d];
      // the F^n halves that end_cycle_positions() summed with the provisional increment
      ext += f_ext_[i] * (du - du_[i]);
      cont += f_cont_[i] * (du - du_[i]);
      v_[i] = du / dt;  // the motion the coupling prescribes
      du_[i] = du;
      u_[i] = target;  // exactly, not up to the round-off of u + dt v
      x_[i] = x0[i] + target;
      if (ghost_omega_set_) {
        omega_[i] = ghost_omega_[3 * k + d];
        dtheta_[i] = dt * omega_[i];
      }
      ghost_work +=
          ghost_reaction_[3 * k + d] * du + ghost_reaction_moment_[3 * k + d] * dtheta_[i];
    }
  ghost_target_set_ = false;
  ghost_omega_set_ = false;
  if (external_loads_) energy_.external_work_J += 0.5 * ext;
  if (!contacts_.empty()) energy_.contact_J -= 0.5 * cont;
  energy_.coupling_work_J += 0.5 * ghost_work;  // the R^n half of the ghosts' reaction work
}

void Solver::rebuild_coupled_nodes() {
  coupled_.reset(n_);
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k)
      if (f_coup_[k] != 0.0 || m_coup_[k] != 0.0) coupled_.insert(i);
}

void Solver::set_mass_override(std::vector<double> mass_kg) {
  mass_override_ = std::move(mass_kg);
}

void Solver::set_ghost_nodes(std::vector<std::int32_t> nodes) {
  ghost_list_ = std::move(nodes);
}

void Solver::set_ghost_displacement(const double* u_next) {
  std::copy(u_next, u_next + ghost_target_.size(), ghost_target_.begin());
  ghost_target_set_ = true;
}

void Solver::set_inertia_override(std::vector<double> inertia_kgm2) {
  inertia_override_ = std::move(inertia_kgm2);
}

void Solver::set_ghost_angular_velocity(const double* omega_mid) {
  std::copy(omega_mid, omega_mid + ghost_omega_.size(), ghost_omega_.begin());
  ghost_omega_set_ = true;
}

Vec3 Solver::net_moment(std::size_t i) const {
  return {-m_int_[3 * i], -m_int_[3 * i + 1], -m_int_[3 * i + 2]};
}

void Solver::add_coupling_moment(std::size_t i, const Vec3& m) {
  mark_coupled(i);
  for (std::size_t d = 0; d < 3; ++d) {
    m_coup_[3 * i + d] += m[d];
    energy_.coupling_work_J += 0.5 * m[d] * dtheta_at(3 * i + d);
  }
}

Vec3 Solver::net_force(std::size_t i) const {
  return {f_ext_[3 * i] + f_cont_[3 * i] - f_int_[3 * i],
          f_ext_[3 * i + 1] + f_cont_[3 * i + 1] - f_int_[3 * i + 1],
          f_ext_[3 * i + 2] + f_cont_[3 * i + 2] - f_int_[3 * i + 2]};
}

void Solver::add_coupling_force(std::size_t i, const Vec3& f) {
  mark_coupled(i);
  for (std::size_t d = 0; d < 3; ++d) {
    f_coup_[3 * i + d] += f[d];
    energy_.coupling_work_J += 0.5 * f[d] * du_at(3 * i + d);  // the F^{n+1} half (see above)
  }
}

void Solver::add_coupling_loads(const std::vector<std::size_t>& nodes, const double* f,
                                const double* m) {
  double work = energy_.coupling_work_J;  // the additions of the one-node calls, in their order
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const std::size_t i = nodes[j];
    mark_coupled(i);
    for (std::size_t d = 0; d < 3; ++d) {
      f_coup_[3 * i + d] += f[3 * j + d];
      work += 0.5 * f[3 * j + d] * du_at(3 * i + d);  // the F^{n+1} half
    }
    if (m != nullptr)
      for (std::size_t d = 0; d < 3; ++d) {
        m_coup_[3 * i + d] += m[3 * j + d];
        work += 0.5 * m[3 * j + d] * dtheta_at(3 * i + d);
      }
  }
  energy_.coupling_work_J = work;
}

void Solver::set_acceleration(std::size_t i, const Vec3& a) {
  mark_coupled(i);
  for (std::size_t d = 0; d < 3; ++d) {
    const double f = mass_[i] * (a[d] - a_[3 * i + d]);  // the link force that makes a
    f_coup_[3 * i + d] += f;
    energy_.coupling_work_J += 0.5 * f * du_at(3 * i + d);
    a_[3 * i + d] = a[d];
  }
}

bool Solver::predict_next_positions(const std::vector<std::size_t>& nodes, double dt_next,
                                    double* u_next, double* omega_mid) const {
  for (const auto i : nodes)
    if (i >= n_ || rigid_node_[i] || ghost_[i] || prescribed_node_[i]) return false;
  // The next step must be one propose_step() and impose_step() will accept (their checks on
  // step_proposal(), the proposal from the stable step at hand), so that a step above the stable
  // limit stops the run before anything computed with it leaves; non-finite values are left to
  // the passes' guard likewise.
  const double proposal = step_proposal();
  if (!(dt_next > 0.0) || dt_next > proposal * (1.0 + 1e-9) || proposal < 1e-4 * dt_min_)
    return false;
  // The expressions of coupling_pass, zero_held, velocity_pass (advance_velocity_into's v + dt a,
  // or advance_velocity's v += dt a: the same update) and advance_displacement, written the same
  // way so that the compiler rounds (and contracts to FMA) alike; LayerStepper compares the
  // result with the passes' to the bit.
  const double dt_mid = mid_step(dt_, dt_next);
  const auto& fixed = model_.fixed;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const std::size_t i = nodes[j];
    const std::uint8_t mask = fixed.empty() ? 0 : fixed[i];
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * i + d;
      const double f = f_ext_[k] + f_cont_[k] + f_coup_[k];
      const double a = (f - f_int_[k]) * inv_mass_[i];
      const double al = (m_coup_[k] - m_int_[k]) * inv_inertia_[i];
      // a held dof's a and alpha are zeroed too, which matters not here: its velocity is 0
      double v = v_[k];
      v += dt_mid * a;
      double w = omega_[k];
      w += dt_mid * al;
      if (mask & (1u << d)) v = 0.0;
      if (mask & (8u << d)) w = 0.0;
#ifdef __FMA__
      u_next[3 * j + d] = std::fma(dt_next, v, u_[k]);
#else
      u_next[3 * j + d] = u_[k] + dt_next * v;
#endif
      if (omega_mid) omega_mid[3 * j + d] = w;
      if (!std::isfinite(u_next[3 * j + d]) || !std::isfinite(w)) return false;
    }
  }
  return true;
}

}  // namespace crashlink::integration
