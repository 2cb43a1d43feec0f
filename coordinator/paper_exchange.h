#pragma once
// The coordinator's run loop core for the `paper` scheme over processes (docs/design.md §2.2-§2.6;
// Bourel 2005 [5]-[11]): every daemon sends its free state; the schedule of docs/design.md §2.6
// (coupling::Schedule) decides which state is answered next; the answer (Correction, [8]-[11]:
// PaperExchange::next) uses the same functions, in the same order, as cosim::PaperRunner, so a run
// over processes reproduces it bit for bit. Steps: PaperExchange::Steps. Guard: check_energies();
// interface history: PaperRow. The session: docs/paper-scheme.md "Over processes".
//
// Limits (each refused where it is found): every coupled node in exactly two domains;
// translations only (cosim::PaperRunner's rule, checked by the daemons).
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "coordinator/paper_cut.h"
#include "coupling/paper_coupling.h"
#include "coupling/paper_guard.h"
#include "coupling/schedule.h"
#include "proto/crashlink.pb.h"

namespace crashlink::coordinator {

/// The end of a `paper` run: the first instant at or after the end time where every domain lands
/// (a multiple of every step). Its fixed steps are never clipped: [11]'s spring
/// M / (dt^n dt^{n-1/2}) on a short last step would spoil the energy balance (the Solver's
/// product-form kinetic energy matches the trapezoid work only at a constant step).
coupling::Tick paper_end_ticks(double end_time_s, const std::vector<coupling::Tick>& steps,
                               std::int64_t ticks_per_second);

/// One interface history row (io::CouplingSample's fields), per interface at every instant both
/// sides were answered: displacement gap and velocity jump (max over the nodes, from the free
/// states), cumulative work of the link forces M (a_link - a_free) and of the drift forces M da on
/// both presences (trapezoid rule, as the Solver counts work), and the resultant link force on the
/// coarse side's presences.
struct PaperRow {
  std::uint32_t interface = 0;
  coupling::Tick time = 0;
  double velocity_jump_m_s = 0.0;   ///< max |v_fine - v_coarse|, v^{n-1/2} of the free states
  double displacement_gap_m = 0.0;  ///< max |u_fine - u_coarse| over the nodes (before [11])
  double link_work_J = 0.0;         ///< cumulative, both presences
  double drift_work_J = 0.0;        ///< cumulative, both presences
  std::array<double, 3> force_N{};  ///< resultant link force on the coarse side's presences
};

class PaperExchange {
 public:
  /// How the steps are chosen: the plan's, fixed (default), or variable (docs/design.md §2.6: each
  /// free state carries its domain's proposal; split imposes the smallest of all at every instant
  /// and, like a single-domain run, stops at the first instant at or after the end time; multi
  /// each its own, the last step clipped to the end time).
  enum class Steps {
    fixed,            ///< the plan's `steps` for the whole run (cosim::PaperRunner's way)
    variable_common,  ///< split: at every instant the smallest proposal of all (docs/design.md
                      ///< §2.6)
    variable_own,     ///< multi: each state's own proposal (FreeState.stable_step_ticks)
  };

  /// steps: [daemons] each domain's step of the plan (fixed; variable: the fallback of a domain
  /// that proposes no limit). Throws ModelError on bad sizes.
  PaperExchange(const PaperCut& cut, const coupling::InterfaceTable& table,
                std::vector<coupling::Tick> steps, coupling::paper::Drift drift, double guard_rise,
                std::int64_t ticks_per_second, Steps policy = Steps::fixed);

  /// Domain k's free state (FreeState: free accelerations [5], displacements, half-step
  /// velocities, its energies at its previous instant). Throws ProtocolError (wrong time, sizes)
  /// and NumericalError (the coupling went unstable).
  void submit(int k, const wire::FreeState& s);
  /// The next correction the schedule allows, as (daemon, Envelope), or nullopt. The correction:
  ///   a* = a_own + [10](a_partner(t_l^j), a_partner(t_l^{j+1}); theta)      ([8], [9] with [10])
  ///        + (u_ref - u) / (dt^n dt^{n-1/2})   on the non-reference side    ([11], switchable)
  /// with u_ref the reference side's displacement interpolated by [10]. Throws NumericalError when
  /// the corrected acceleration is not finite (nothing non-finite is ever sent).
  std::optional<std::pair<int, wire::Envelope>> next();
  /// History rows completed since the last call.
  std::vector<PaperRow> take_rows();

  /// Domain k's energies at its last instant (they come with its Bye: no free state follows).
  /// Throws ProtocolError unless `time` is its last state's, NumericalError as submit().
  void final_energy(int k, const wire::EnergyTerms& e, coupling::Tick time);

  /// The instant of domain k's latest free state (0 before the first).
  coupling::Tick latest(int k) const { return domains_[static_cast<std::size_t>(k)].latest; }
  bool all_finished() const { return schedule_.all_finished(); }
  /// Domain k was answered with stop (it may say Bye now).
  bool finished(int k) const { return schedule_.finished(k); }
  /// The run's end instant: paper_end_ticks (fixed steps) or the end time in ticks (variable).
  coupling::Tick end_ticks() const { return schedule_.end_time(); }

 private:
  struct Slot {
    coupling::Tick time = -1;
    std::vector<double> a, u, v;  // [3n] free acceleration, displacement, v^{n-1/2}
  };
  struct Group {  // the nodes of one domain coupled to partner l
    int partner = -1;
    std::vector<std::size_t> mine, theirs;  // node indices in each Register order
  };
  struct Domain {
    std::size_t n = 0;
    std::vector<double> mass_kg;           // [n] M
    std::vector<std::uint8_t> ref;         // [n] 1: reference side of [11]
    std::vector<std::uint32_t> interface;  // [n]
    std::vector<Group> groups;
    Slot slot[2];
    coupling::Tick prev_step = 0, latest = 0, answered = -1;  // ticks
    std::int64_t submitted = 0;                               // free states so far
    std::vector<double> f_link, f_drift, u_last;              // [3n] work bookkeeping
    std::map<coupling::Tick, wire::EnergyTerms> energy;
  };
  struct Itf {
    int fine = -1, coarse = -1;
    std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (fine node, coarse node)
    double link_J = 0.0, drift_J = 0.0;
    std::array<double, 3> force_N{};
    coupling::Tick row_time = -1;
  };

  double seconds(coupling::Tick t) const;
  [[noreturn]] void unstable(coupling::Tick t, const std::string& what) const;
  /// At every instant where all domains stand together (their energies arrive with their next
  /// free state; with variable multi steps, whenever the oldest of the domains' latest energies
  /// advances, their sum) the energy guard (coupling/paper_guard.h) checks the coupled energy; a
  /// rise, or a non-finite free or corrected acceleration, throws NumericalError "the coupling
  /// went unstable".
  void check_energies();
  void add_rows(int k, coupling::Tick t);

  const PaperCut& cut_;
  std::vector<coupling::Tick> steps_;
  Steps policy_;
  coupling::Tick guard_time_ = -1;  // variable_own: the last instant the guard sampled
  coupling::paper::Drift drift_;
  std::int64_t tps_;
  coupling::Schedule schedule_;
  std::vector<Domain> domains_;
  std::vector<Itf> interfaces_;
  coupling::paper::EnergyGuard guard_;
  bool have_initial_ = false;
  double initial_J_ = 0.0, twice0_J_ = 0.0;
  std::vector<PaperRow> rows_;
  // scratch, [3 x group size]
  std::vector<double> own_, lo_, hi_, out_, ulo_, uhi_, uref_g_;
  std::vector<double> a_link_, u_ref_, da_, a_star_;
};

}  // namespace crashlink::coordinator
