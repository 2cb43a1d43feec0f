#pragma once
// The `multi` mode of the `layer` scheme (DESIGN.md §2.3, §2.6, §2.7 "How to distribute layer")
// for two domains in one process, each at its own step: the reference algorithm is LRunner of
// coupling-study/layer-check/layer.py, mode 'grid', natural viscous form 'L'.
//
// partition::decompose(global, Layer) gives a fine domain F (it took the coarse side's first
// element layer and holds the layer's far nodes J as ghosts) and a coarse domain C (owns J with
// its natural summed mass). Time is an integer count of ticks (coordinator/ticks.h): F steps h on
// the grid k h, C steps H. Both steps are fixed for the run (see Options; variable steps: not
// yet). Per coarse step [T, T+H], in one process:
//   C.begin_cycle() (T), F.begin_cycle() (its last instant t0 <= T): energies sampled here;
//   C.end_cycle_forces(): u_J(T+H) and C's force g_B(T+H) on J;
//   F's fine steps up to T+H, J prescribed linear in time between u_J(T) and u_J(T+H)
//     (set_ghost_displacement at every fine instant; shell J: C's omega^{T+H/2}, constant over
//     the coarse step, via set_ghost_angular_velocity);
//   g_A(T+H) = F's net force (and moment) on J at T+H: F lands on every coarse instant, so H/h
//     must be a whole number (initialize() throws otherwise, or rounds H down to a multiple of h
//     with Options::integer_ratio). Non-integer ratios (LRunner: g_A linear between F's instants
//     t0 < T+H < t1, the force at t1 computed with J continuing at its old velocity) need a
//     Solver hook that evaluates a trial configuration without advancing: not available yet;
//   C.add_coupling_force(J, g_A(T+H)) between C's two halves: a_J = (g_B + g_A) / M_J ([8]).
// The distributed version overlaps F's fine steps with C's step; here they take turns.
// Each domain's energy account holds its coupling work (C: the work of g_A on J; F: the work of
// J's prescribed motion on F); energy() is their sum.
#include <cstdint>
#include <functional>
#include <vector>

#include "coordinator/ticks.h"
#include "solver/cosim/layer_domains.h"

namespace crashlink::cosim {

struct MultirateOptions {
  double fine_dt_s = 0.0;    ///< F's step h; 0: F's initial proposal (rounded down to ticks)
  double coarse_dt_s = 0.0;  ///< C's step H; 0: C's initial proposal (rounded down to ticks)
  /// Round H down to a whole multiple of h (F lands on every coarse instant).
  bool integer_ratio = false;
  /// ratio_p > 0: impose H/h = ratio_p/ratio_q exactly (whole ticks) instead of the two steps
  /// above, with h the largest multiple of ratio_q ticks under step_safety * min(F's proposal,
  /// C's proposal * ratio_q / ratio_p).
  int ratio_p = 0, ratio_q = 1;
  /// Margin on the initial proposals for ratio_p (the stable step shrinks as the mesh deforms
  /// and bulk viscosity acts; a fixed step above a later proposal makes impose_step throw).
  double step_safety = 1.0;
  std::int64_t ticks_per_second = coordinator::kDefaultTicksPerSecond;
};

class MultirateRunner {
 public:
  /// Cuts `global` (which must outlive the runner); throws ModelError unless the cut gives exactly
  /// two non-empty domains, one holding every ghost (F) and the other owning them (C).
  explicit MultirateRunner(const model::Model& global, MultirateOptions options = {});
  MultirateRunner(const MultirateRunner&) = delete;
  MultirateRunner& operator=(const MultirateRunner&) = delete;

  /// t = 0 in both domains, the t = 0 exchange on J, and the fixed steps h and H (ModelError if
  /// H < h or H/h is not a whole number). Either step may never exceed its domain's proposal
  /// (Solver::impose_step throws).
  void initialize();
  /// One coarse step T -> T+H. `on_fine` is called after every begin_cycle() of F (F's state at
  /// its instant t^n complete; C's begun at T on the first call of the step, then at T+H's forces).
  void advance(const std::function<void()>& on_fine = {});

  coordinator::Tick fine_step_ticks() const { return h_; }
  coordinator::Tick coarse_step_ticks() const { return H_; }
  double fine_dt_s() const { return seconds(h_); }
  double coarse_dt_s() const { return seconds(H_); }
  coordinator::Tick coarse_time_ticks() const { return tC_; }
  coordinator::Tick fine_time_ticks() const { return tF_; }
  double seconds(coordinator::Tick n) const {
    return static_cast<double>(n) / static_cast<double>(options_.ticks_per_second);
  }
  std::int64_t fine_steps() const { return fine_steps_; }

  /// Sum of both energy accounts, sampled at the start of the last advance() (C at T, F at its
  /// last instant <= T). Mass and kinetic energy of J are counted once (owner C).
  const integration::EnergyAccount& energy() const { return energy_; }
  const integration::Solver& fine() const { return *d_.solvers[f_]; }
  const integration::Solver& coarse() const { return *d_.solvers[c_]; }
  const partition::Decomposition& decomposition() const { return d_.dec; }
  /// Global node g's owner: 0 = F, 1 = C, and its local index there.
  bool owned_by_fine(std::size_t g) const { return d_.owner_solver[g] == f_; }
  std::size_t local_index(std::size_t g) const { return d_.owner_local[g]; }
  /// [3 n_global] displacement of every global node from its owner (F possibly at another time).
  std::vector<double> global_displacement() const { return cosim::global_displacement(d_); }

 private:
  coordinator::Tick to_ticks(double t_s) const;
  void fine_step(const std::vector<double>& uJ_T, const std::vector<double>& uJ_1,
                 const std::vector<double>& omega);
  void coupling_loads(std::vector<Vec3>& force, std::vector<Vec3>& moment);

  MultirateOptions options_;
  LayerDomains d_;
  std::size_t f_ = 0, c_ = 1;
  coordinator::Tick h_ = 0, H_ = 0, tF_ = 0, tC_ = 0;
  std::int64_t fine_steps_ = 0;
  std::vector<double> scratch_;
  integration::EnergyAccount energy_;
};

}  // namespace crashlink::cosim
