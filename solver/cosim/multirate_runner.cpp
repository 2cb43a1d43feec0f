// MultirateRunner: the `layer` scheme's `multi` mode for two domains in one process
// (multirate_runner.h; DESIGN.md §2.3, §2.6, §2.7; LRunner of coupling-study/layer-check).
#include "solver/cosim/multirate_runner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "solver/core/errors.h"

namespace crashlink::cosim {

MultirateRunner::MultirateRunner(const model::Model& global, MultirateOptions options)
    : options_(options), d_(build_layer_domains(global, "multirate")) {
  if (d_.solvers.size() != 2)
    throw ModelError("multirate: the layer cut gives " + std::to_string(d_.solvers.size()) +
                     " non-empty domains; this runner couples exactly two (fine and coarse)");
  if (d_.ghosts[0].empty() == d_.ghosts[1].empty())
    throw ModelError(
        "multirate: exactly one of the two domains must hold the ghost nodes J (the fine one)");
  f_ = d_.ghosts[0].empty() ? 1 : 0;
  c_ = 1 - f_;
  if (options_.ticks_per_second < 1) throw ModelError("multirate: ticks_per_second must be >= 1");
}

coordinator::Tick MultirateRunner::to_ticks(double t_s) const {
  // coordinator::TickClock::to_ticks' rule (round down, snap within 4 ulps of a whole tick);
  // cosim does not link crashlink::coordinator, so the two lines are repeated here.
  if (!std::isfinite(t_s) || !(t_s > 0.0))
    throw NumericalError("multirate: step " + std::to_string(t_s) + " s is not positive");
  const double x = t_s * static_cast<double>(options_.ticks_per_second);
  const double nearest = std::nearbyint(x);
  const double snap = 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, x);
  const double n = std::abs(x - nearest) <= snap ? nearest : std::floor(x);
  if (n < 1.0 || n > 4.6e18)
    throw ModelError("multirate: step " + std::to_string(t_s) +
                     " s is not representable in ticks; change ticks_per_second");
  return static_cast<coordinator::Tick>(n);
}

void MultirateRunner::initialize() {
  auto& F = *d_.solvers[f_];
  auto& C = *d_.solvers[c_];
  F.initialize();
  C.initialize();
  exchange_initial_forces(d_);
  if (options_.ratio_p > 0) {
    if (options_.ratio_q < 1 || !(options_.step_safety > 0.0 && options_.step_safety <= 1.0))
      throw ModelError("multirate: ratio_q must be >= 1 and step_safety in (0, 1]");
    const double p = options_.ratio_p, q = options_.ratio_q;
    const coordinator::Tick unit =
        to_ticks(options_.step_safety * std::min(F.dt_s(), C.dt_s() * q / p)) / options_.ratio_q;
    if (unit < 1) throw ModelError("multirate: the fine step is shorter than ratio_q ticks");
    h_ = unit * options_.ratio_q;
    H_ = unit * options_.ratio_p;
  } else {
    h_ = to_ticks(options_.fine_dt_s > 0.0 ? options_.fine_dt_s : F.dt_s());
    H_ = to_ticks(options_.coarse_dt_s > 0.0 ? options_.coarse_dt_s : C.dt_s());
  }
  if (options_.integer_ratio) H_ = (H_ / h_) * h_;
  if (H_ % h_ != 0)
    throw ModelError("multirate: H / h = " + std::to_string(H_) + " / " + std::to_string(h_) +
                     " ticks is not a whole number; non-integer ratios need the fine domain's "
                     "force at a trial instant (not available yet); fix: integer_ratio = true");
  if (H_ < h_)
    throw ModelError("multirate: the coarse step (" + std::to_string(seconds(H_)) +
                     " s) is shorter than the fine step (" + std::to_string(seconds(h_)) +
                     " s); the domain holding J must be the fine one");
  F.impose_step(seconds(h_));
  C.impose_step(seconds(H_));
  tF_ = tC_ = 0;
  fine_steps_ = 0;
  scratch_.assign(3 * d_.ghosts[f_].size(), 0.0);
  energy_ = integration::EnergyAccount{};
}

void MultirateRunner::fine_step(const std::vector<double>& uJ_T, const std::vector<double>& uJ_1,
                                const std::vector<double>& omega) {
  // J prescribed linear in time over [T, T+H] (LRunner: Unext = uJ_T + (t1 - T)/H (uJ_1 - uJ_T)).
  auto& F = *d_.solvers[f_];
  const coordinator::Tick t1 = tF_ + h_;
  const double w = static_cast<double>(t1 - tC_) / static_cast<double>(H_);
  if (t1 == tC_ + H_)
    scratch_ = uJ_1;  // exactly C's u(T+H): at H = h this is the split cycle to the bit
  else
    for (std::size_t i = 0; i < scratch_.size(); ++i)
      scratch_[i] = uJ_T[i] + w * (uJ_1[i] - uJ_T[i]);
  F.set_ghost_displacement(scratch_.data());
  F.set_ghost_angular_velocity(omega.data());
  F.end_cycle_forces();
  F.end_cycle_accelerations();
  F.impose_step(seconds(h_));
  tF_ = t1;
  ++fine_steps_;
}

void MultirateRunner::coupling_loads(std::vector<Vec3>& force, std::vector<Vec3>& moment) {
  // The layer's force and moment on J at T+H (C's forces are already there).
  const auto& F = *d_.solvers[f_];
  const auto& gl = d_.ghosts[f_];
  const coordinator::Tick T1 = tC_ + H_;
  force.resize(gl.size());
  moment.resize(gl.size());
  for (std::size_t j = 0; j < gl.size(); ++j) {
    force[j] = F.net_force(gl[j].local);
    moment[j] = F.net_moment(gl[j].local);
  }
  // F has an instant at T+H: the ratio is a whole number (initialize() checks it). A non-integer
  // ratio needs the layer force at the trial instant t0 + h > T+H with J continuing at its old
  // velocity, then linear in time (LRunner 'grid'): that needs a Solver hook that evaluates a
  // trial configuration without advancing (the Solver is not copyable); see the report.
  if (tF_ != T1) throw NumericalError("multirate: the fine domain missed the coarse instant");
}

void MultirateRunner::advance(const std::function<void()>& on_fine) {
  auto& F = *d_.solvers[f_];
  auto& C = *d_.solvers[c_];
  const auto& gl = d_.ghosts[f_];
  C.begin_cycle();  // T
  F.begin_cycle();  // t0 <= T
  energy_ = sum_energies(d_, energy_.reference_J);
  if (on_fine) on_fine();
  const std::size_t n3 = 3 * gl.size();
  std::vector<double> uJ_T(n3), uJ_1(n3), omega(n3);
  for (std::size_t j = 0; j < gl.size(); ++j)
    for (std::size_t d = 0; d < 3; ++d) {
      uJ_T[3 * j + d] = C.displacement()[3 * gl[j].owner_local + d];
      omega[3 * j + d] = C.angular_velocity_mid()[3 * gl[j].owner_local + d];  // omega^{T+H/2}
    }
  C.end_cycle_forces();  // u(T+H), C's forces at T+H
  for (std::size_t j = 0; j < gl.size(); ++j)
    for (std::size_t d = 0; d < 3; ++d)
      uJ_1[3 * j + d] = C.displacement()[3 * gl[j].owner_local + d];
  const coordinator::Tick T1 = tC_ + H_;
  bool begun = true;
  while (tF_ + h_ <= T1) {
    if (!begun) {
      F.begin_cycle();
      if (on_fine) on_fine();
    }
    begun = false;
    fine_step(uJ_T, uJ_1, omega);
  }
  std::vector<Vec3> force, moment;
  coupling_loads(force, moment);
  for (std::size_t j = 0; j < gl.size(); ++j) {  // [8]: a_J = (g_B + g_A) / M_J
    C.add_coupling_force(gl[j].owner_local, force[j]);
    C.add_coupling_moment(gl[j].owner_local, moment[j]);
  }
  C.end_cycle_accelerations();
  C.impose_step(seconds(H_));
  tC_ = T1;
}

}  // namespace crashlink::cosim
