#pragma once
// The `paper` coupling scheme exactly as Bourel, Combescure & Di Valentin (2005) write it
// ([5]-[11]; docs/design.md §2.2-§2.5; scheme S1 of coupling-study/mts.py), for two domains in one
// process, each at its own fixed step, the coarse step H a whole multiple r of the fine step h.
// Kept for comparison with `layer` (the default): the study and docs/design.md §2.7 say where it
// fails; the guard stops a run that goes unstable with a NumericalError saying so. The measured
// numbers: docs/paper-scheme.md "Measured".
//
// The cut and the summed masses [5]: the constructor. One coarse step, [8]-[11]: advance(). The
// guard: sample_energy(). Time is an integer count of ticks (coupling/ticks.h).
// Limits: translations only (a link node with rotary inertia, i.e. a shell node shared by both
// domains, is refused: the Solver has no hook to impose a corrected angular acceleration); fixed
// steps; integer ratio H/h (else ModelError).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coupling/coupling_config.h"
#include "coupling/paper_coupling.h"
#include "coupling/paper_guard.h"
#include "coupling/ticks.h"
#include "solver/integration/energy.h"
#include "solver/integration/solver.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::cosim {

struct PaperOptions {
  double fine_dt_s = 0.0;    ///< F's step h; 0: F's initial proposal (rounded down to ticks)
  double coarse_dt_s = 0.0;  ///< C's step H; 0: C's initial proposal (rounded down to ticks)
  /// Round H down to a whole multiple of h (F lands on every coarse instant).
  bool integer_ratio = false;
  /// ratio_p > 0: impose H/h = ratio_p / ratio_q (whole ticks) instead of the two steps above,
  /// with h the largest multiple of ratio_q ticks under step_safety * min(F's proposal,
  /// C's proposal * ratio_q / ratio_p). Only whole ratios run (ratio_p a multiple of ratio_q).
  int ratio_p = 0, ratio_q = 1;
  double step_safety = 1.0;  ///< margin on the initial proposals for ratio_p, in (0, 1]
  /// How the domains couple: the configuration a run over processes has
  /// (coupling/coupling_config.h), of which the runner reads drift ([11] on the non-reference
  /// side every step, the paper; off: the study's S2), guard_rise (stop when the coupled energy
  /// rises this fraction of the peak energy above its running minimum; 0 or negative: no energy
  /// check, the non-finite check always runs) and ticks_per_second; scheme must be "paper" and
  /// variable_steps false (ModelError otherwise). Checkpoints, restart and lanes are the
  /// processes' (not read). Two domains, fixed steps.
  coupling::CouplingConfig run{.scheme = "paper", .common_step = false};
};

/// One node coupled between the two domains: a link node (present in both with its partial
/// masses) or a copy (in the master's domain) of a slave node (the original).
struct PaperNode {
  std::size_t global = 0;         ///< global node index
  std::size_t local[2] = {0, 0};  ///< local index in [0] the fine and [1] the coarse solver
  double mass_kg = 0.0;           ///< M = sum_k m^k ([5])
  int reference = 1;              ///< side of [11]'s reference: 0 fine, 1 coarse
  bool copy = false;              ///< a contact copy (§3.1) rather than a shared link node
};

/// Largest distance between the two presences of a coupled node at a coarse instant [m].
struct PaperGap {
  double link_m = 0.0;  ///< over link nodes
  double copy_m = 0.0;  ///< over contact copies and their originals
};

class PaperRunner {
 public:
  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);

  /// Cuts `global` (which must outlive the runner) with the paper scheme; throws ModelError unless
  /// the cut gives exactly two non-empty domains coupled by at least one node.
  /// Cut: partition::decompose(global, Paper): no element moves; a node used by both domains (a
  /// link) is present in both; for a contact across domains the master's domain holds copies of
  /// the other domain's slave nodes (no elements, no own mass). Every coupled node is integrated in
  /// both domains with the SUMMED mass M = sum_k m^k ([5]; coupling::paper::summed_mass over the
  /// partial lumped masses) through Solver::set_mass_override. Reference side of [11]: the coarse
  /// domain for a link, the original's domain for a copy (Interface::reference).
  explicit PaperRunner(const model::Model& global, PaperOptions options = {});
  PaperRunner(const PaperRunner&) = delete;
  PaperRunner& operator=(const PaperRunner&) = delete;

  /// t = 0 in both domains and the fixed steps h and H (ModelError if H < h or H/h is not a whole
  /// number). The t = 0 correction happens at the start of the first advance().
  void initialize();
  /// One coarse step [T, T+H]:
  ///   entry: both domains at T with their FREE accelerations a_F(T), a_C(T) ([5]) and u(T);
  ///   C at T: a* = a_C(T) + a_F(T) ([8]) (+ [11] on nodes where C is the non-reference side, with
  ///           u_ref = u_F(T): F has an instant at T);
  ///   F at T: a* = a_F(T) + a_C(T) ([8]) (+ [11] where F is non-reference, u_ref = u_C(T));
  ///   both begin_cycle() (energies at T: the guard runs here); C steps to T+H: free state at T+H;
  ///   F's fine steps t = T + k h, k = 1..r-1: a* = a_F(t) + [10](a_C(T), a_C(T+H); k/r) ([9])
  ///           (+ [11] with u_ref = [10](u_C(T), u_C(T+H); k/r) where F is non-reference);
  ///   F's last fine step lands on T+H with its free state: the next advance() starts there.
  /// This is the earliest-pending-state order of docs/design.md §2.6 (ties: both at T answered
  /// together). The corrections reach the solvers through Solver::set_acceleration: the implied
  /// force M (a* - a_free) - link [8]-[10] and drift [11] together - is counted in each domain's
  /// coupling_work_J (trapezoid rule, like every work term of energy.h). `on_fine` is called after
  /// every begin_cycle() of F, i.e. at F's instants T, T+h, ..., T+H-h (C begun at T: its state is
  /// at T on the first call, its forces at T+H on the later ones). Throws NumericalError "the
  /// coupling went unstable" (guard).
  void advance(const std::function<void()>& on_fine = {});

  coupling::Tick fine_step_ticks() const { return h_; }
  coupling::Tick coarse_step_ticks() const { return H_; }
  double fine_dt_s() const { return seconds(h_); }
  double coarse_dt_s() const { return seconds(H_); }
  std::int64_t ratio() const { return h_ > 0 ? H_ / h_ : 0; }
  coupling::Tick coarse_time_ticks() const { return tC_; }
  coupling::Tick fine_time_ticks() const { return tF_; }
  double seconds(coupling::Tick n) const {
    return static_cast<double>(n) / static_cast<double>(options_.run.ticks_per_second);
  }
  std::int64_t fine_steps() const { return fine_steps_; }
  std::int64_t coarse_steps() const { return coarse_steps_; }

  /// Both domains' energy accounts at the start of the last advance() (both at T), summed, with
  /// the coupled nodes' kinetic energy counted once (the non-reference side's: the
  /// presence [11] acts on) and coupling_work_J the
  /// net work of the link and drift corrections (the domains' coupling work minus the change of
  /// the kinetic energy counted twice). Its balance_J() stays ~0 (each domain's closes).
  const integration::EnergyAccount& energy() const { return energy_; }
  /// Work of the drift corrections [11] alone, both domains (part of their coupling work) [J].
  double drift_work_J() const { return drift_work_J_; }
  /// Gaps between the presences of the coupled nodes at the start of the last advance() (both at
  /// T; before its correction), and the largest seen since initialize().
  const PaperGap& gap() const { return gap_; }
  const PaperGap& max_gap() const { return max_gap_; }

  const integration::Solver& fine() const { return *solvers_[0]; }
  const integration::Solver& coarse() const { return *solvers_[1]; }
  const partition::Decomposition& decomposition() const { return dec_; }
  const std::vector<PaperNode>& coupled_nodes() const { return nodes_; }
  /// Local index of global node g in the fine / coarse solver (a copy included), or kAbsent.
  std::size_t fine_local(std::size_t g) const { return g2l_[0][g]; }
  std::size_t coarse_local(std::size_t g) const { return g2l_[1][g]; }
  /// [3 n_global] displacement of every global node from its primary presence: the reference side
  /// for a coupled node, the only presence otherwise (F possibly at another instant than C).
  std::vector<double> global_displacement() const;

 private:
  coupling::paper::Drift drift() const {
    return options_.run.drift ? coupling::paper::Drift::on : coupling::paper::Drift::off;
  }
  coupling::Tick to_ticks(double t_s) const;
  void read_free(int side);
  void correct(int side, const std::vector<double>& a_link, const std::vector<double>& u_ref,
               double step_product);
  /// Guard (docs/design.md §7 rule 10): at every coarse instant, the coupled energy
  ///   E = sum_k (KE + IE + HG + contact)_k - the reference side's KE of the coupled nodes (counted
  ///       twice otherwise) - external work
  /// (= initial energy + net work of the coupling) is compared with its running minimum; a rise
  /// above guard_rise x the peak energy, or any non-finite free or corrected acceleration
  /// (check_finite), ends the run with a NumericalError "the coupling went unstable" (scheme,
  /// ratio, time, fix). No NaN is ever written into a solver.
  void sample_energy();
  [[noreturn]] void unstable(const std::string& what) const;
  void check_finite(const std::vector<double>& a, int side, const char* what) const;

  const model::Model& global_;
  PaperOptions options_;
  partition::Decomposition dec_;
  std::unique_ptr<integration::Solver> solvers_[2];  // [0] fine, [1] coarse
  int domain_[2] = {-1, -1};                         // decomposition domain of each side
  std::vector<std::size_t> g2l_[2];                  // [n_global] local index or kAbsent
  std::vector<PaperNode> nodes_;
  coupling::Tick h_ = 0, H_ = 0, tF_ = 0, tC_ = 0;
  std::int64_t fine_steps_ = 0, coarse_steps_ = 0;

  // Interface vectors, [3 x coupled nodes], xyz interleaved.
  std::vector<double> a_free_[2], u_[2];  // current free acceleration and displacement per side
  std::vector<double> aC_lo_, aC_hi_, uC_lo_, uC_hi_;  // C's free states at T and T+H
  std::vector<double> a_link_, u_ref_, da_, a_star_;   // scratch
  std::vector<double> u_last_[2], fd_last_[2];         // drift work bookkeeping per side

  integration::EnergyAccount energy_;
  double ke_twice0_ = 0.0;                       // kinetic energy counted twice at t = 0
  std::vector<std::size_t> reference_nodes_[2];  // local indices of the reference presences
  coupling::paper::EnergyGuard guard_;
  double drift_work_J_ = 0.0;
  PaperGap gap_, max_gap_;
};

}  // namespace crashlink::cosim
