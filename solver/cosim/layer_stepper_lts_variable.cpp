// LayerStepper's `lts` form with variable steps (layer_stepper.h LayerForm; docs/multirate.md
// "Variable steps under lts"): owner steps announced one ahead, the ghost path reflected in time
// across owner steps of different lengths, Fbar weighed by the owner steps on either side.
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <span>
#include <utility>

#include "core/errors.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::cosim {

namespace {
/// More fine substeps per owner step than any mesh ratio a cut plans (a partner's step that
/// would need more is refused: the path holds a row per substep).
constexpr std::int64_t kMaxLtsSubsteps = 100000;
}  // namespace

bool LayerStepper::lts_decide_next_owner_step() {
  // The u_J of the current owner step's end carries the owner's next step
  // (LayerMessage::next_step): taken when the landing substep consumes it, or, by a domain with
  // holders that must announce its own step after that instant, when it is at the inbox front.
  if (next_owner_known_) return true;
  const std::string& dom = solver_.domain_name();
  const Tick end = owner_T_ + owner_H_;
  Tick next = 0;
  bool last = false, pause = false, first = true;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (!port.fine_side) continue;
    const auto& ps = state_[p];
    Tick t = 0, n = 0;
    bool l = false, pa = false;
    if (ps.have_u1 && ps.T1 == end) {
      t = ps.T1, n = ps.next_step_1, l = ps.last_1, pa = ps.pause_1;
    } else if (!ps.inbox.empty()) {
      const auto& m = ps.inbox.front();
      t = m.time, n = m.next_step, l = m.last, pa = m.pause;
    } else {
      wait_iface_ = port.index;
      return false;
    }
    if (t != end)
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: the owner '{}' sent u_J for t = {} ticks, but the "
          "owner step [{}, {}] ticks it announced ends at {} ticks (lts, variable steps)",
          dom, port.index, port.partner, t, owner_T_, end, end));
    if (!l && (n <= 0 || n > std::numeric_limits<Tick>::max() - end))
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: the owner '{}' sent u_J for t = {} ticks with the "
          "next step {} ticks; under lts with variable steps every u_J but the last announces "
          "the owner's step after it, > 0 and within the tick range",
          dom, port.index, port.partner, t, n));
    if (!first && (n != next || l != last || pa != pause))
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: the owner '{}' announces the step {} ticks after "
          "t = {} ticks (last {}, pause {}), another of its interfaces {} ticks ({}, {}); one "
          "owner has one step",
          dom, port.index, port.partner, n, t, l, pa, next, last, pause));
    first = false;
    next = n, last = l, pause = pa;
  }
  owner_last_ = last;
  owner_pause_ = pause;
  if (!last) {
    // ceil(H / p) substeps, p the proposal sent with the Fbar the owner chose H from
    // (layer_stepper.h "Steps": a follower's rule; H = m p gives m substeps, not m + 1 when the
    // proposal fell since). The later substeps may exceed the proposal of the moment, never the
    // stable step (Solver::impose_committed_step).
    const Tick prop = proposal_sent_;
    next_owner_H_ = next;
    next_substeps_ = prop > 0 ? std::max<Tick>(1, next / prop + (next % prop != 0 ? 1 : 0)) : 1;
    if (next_substeps_ > kMaxLtsSubsteps) {
      const auto owner = std::find_if(ports_.begin(), ports_.end(),
                                      [](const LayerPort& p) { return p.fine_side; });
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': the owner '{}' announces the step {} ticks after t = {} ticks, "
          "{} of this domain's proposal {} ticks; at most {} substeps per owner step (the "
          "reflected path holds one row each)",
          solver_.domain_name(), owner->partner, next, end, next_substeps_, prop, kMaxLtsSubsteps));
    }
  }
  next_owner_known_ = true;
  return true;
}

bool LayerStepper::lts_step_after(std::int64_t index, Tick next, Tick& after) {
  if (!follower_) {
    // A leader's choice, its rise limited against the step it takes next; at t = 0 free, as
    // `layer`'s first. The plan's first owner step is the rule's choice from the same proposals
    // (coupling::lts_variable_first_proposals), so the two agree to a tick. (While the plan took
    // the ceil rule's kind, the free choice jumped the fine step by 38 % after the first owner step
    // on a bar started at 30 m/s at one end, -4.4 % of energy balance; held against the plan's
    // step, the rule's hysteresis kept it for tens of steps and then fell 28 % at once.)
    const Tick taken = std::exchange(h_, t_ == 0 ? 0 : next);
    after = choose_step();
    h_ = taken;
    return true;
  }
  if (index + 1 < substeps_) {
    after = substep_length(owner_H_, substeps_, index + 1);
    return true;
  }
  if (!lts_decide_next_owner_step()) return false;
  after = owner_last_ ? 0 : substep_length(next_owner_H_, next_substeps_, 0);
  return true;
}

bool LayerStepper::lts_plan_next(Tick& next) {
  // At the instant t_ (the partners' forces in): the step to take next and, for a domain with
  // holders, the one after it (announced_, sent with u_J(t_ + next)). A leader takes the step it
  // announced at the instant before (the plan's at t = 0); a follower the next substep of its
  // owner step, or at its end the first of the owner step announced with the u_J it landed on.
  // It may wait (false) after taking up that next owner step (a domain with holders whose new
  // owner step has one substep waits for the u_J at its end); taking it up is done once
  // (t_ == owner_T_ afterwards), so the call after the wait finds the same step.
  std::int64_t index = 0;
  if (!follower_) {
    next = announced_;
  } else {
    if (t_ == owner_T_ + owner_H_) {
      if (!lts_decide_next_owner_step()) return false;
      if (owner_last_) {  // the run ends here, with the owner
        next = 0;
        return true;
      }
      owner_T_ = t_;
      owner_H_ = next_owner_H_;
      substeps_ = next_substeps_;
      substep_ = 0;
      next_owner_known_ = false;
      // the owner pauses where this owner step starts: so does this side, before any substep
      // (pause_here); owner_pause_ is then the next end's, which a domain with holders whose
      // owner step has one substep decides below, in this same call
      lts_pause_at_ = owner_pause_ ? t_ : -1;
      owner_pause_ = false;
    }
    index = t_ == owner_T_ ? 0 : substep_ + 1;
    next = substep_length(owner_H_, substeps_, index);
  }
  // A leader's announced_ is also its own next step: it chooses one with holders or without.
  Tick after = 0;
  const bool holders =
      std::any_of(ports_.begin(), ports_.end(), [](const LayerPort& p) { return !p.fine_side; });
  if ((holders || !follower_) && !lts_step_after(index, next, after)) return false;
  if (follower_) substep_ = index;
  announced_ = after;
  return true;
}

void LayerStepper::lts_ghost_targets_variable(const LayerPort& port, PortState& ps, Tick t1) {
  // J at t1, the end of substep q of p in the owner step [T, T + H]: the owner's u_J(T + H) at
  // q = p; else the path reflected in time, U(t1) = 2 u_J(T) - U(2T - t1), U of the owner step
  // before interpolated linearly between its instants (the fixed form's row where the steps are
  // equal; before its first instant, extrapolated from its first two); frozen at u_J(0) over
  // the first owner step (the start, as fixed).
  const std::size_t n3 = 3 * port.local.size();
  const auto p = static_cast<std::size_t>(substeps_);
  const auto q = static_cast<std::size_t>(substep_ + 1);
  const Tick T = ps.T;
  CRASHLINK_ASSERT(T == owner_T_ && q <= p && ps.path_cur_t.size() == p + 1);
  ps.path_cur_t[q] = t1;
  const bool lands = q == p;
  const bool reflect = !lands && T != 0;
  std::size_t k = 0;  // rows k, k + 1 of the step before around the mirror instant
  double w = 0.0;     // the weight of row k + 1
  const auto& tt = ps.path_prev_t;
  if (reflect) {
    const Tick tm = 2 * T - t1;
    while (k + 2 < tt.size() && tt[k + 1] <= tm) ++k;
    w = static_cast<double>(tm - tt[k]) / static_cast<double>(tt[k + 1] - tt[k]);
  }
  // omega over [t_, t1] (small rotations): the mean of the step before's over the mirror
  // interval [2T - t1, 2T - t_] (its substeps' omega, piecewise constant, the first one's before
  // it); over the last substep what lands on the owner's rotation Theta(T) + H omega_J(T + H/2):
  // (H omega_J - sum_k h_k omega_k) / h_q.
  const Tick h = t1 - ps.path_cur_t[q - 1];
  auto& ov = lts_overlap_;
  ov.clear();
  if (ps.rotates && reflect) {
    const Tick a = 2 * T - t1, b = 2 * T - ps.path_cur_t[q - 1];
    for (std::size_t j = 0; j + 1 < tt.size(); ++j) {
      const Tick lo = std::max(j == 0 ? a : tt[j], a), hi = std::min(tt[j + 1], b);
      if (hi > lo) ov.emplace_back(j, static_cast<double>(hi - lo) / static_cast<double>(b - a));
    }
  }
  const double H = static_cast<double>(owner_H_);
  for (std::size_t j = 0; j < port.local.size(); ++j) {
    const std::size_t s = ghost_slot_[port.local[j]];
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t i = 3 * j + d;
      double u = ps.u_T[i];
      if (lands) {
        u = ps.u_1[i];
      } else if (reflect) {
        const double a = ps.path_prev[k * n3 + i], b = ps.path_prev[(k + 1) * n3 + i];
        u = 2.0 * ps.u_T[i] - (a + w * (b - a));
      }
      ps.path_cur[q * n3 + i] = u;
      ghost_u_[3 * s + d] = u;
      double om = 0.0;
      if (ps.rotates) {
        if (lands) {
          double sum = H * (ps.omega.empty() ? 0.0 : ps.omega[i]);
          for (std::size_t m = 0; m + 1 < q; ++m)
            sum -= static_cast<double>(ps.path_cur_t[m + 1] - ps.path_cur_t[m]) *
                   ps.omega_cur[m * n3 + i];
          om = sum / static_cast<double>(h);
        } else {
          for (const auto& [m, f] : ov) om += f * ps.omega_prev[m * n3 + i];
        }
        ps.omega_cur[(q - 1) * n3 + i] = om;
      }
      ghost_omega_[3 * s + d] = om;
    }
  }
}

void LayerStepper::lts_next_owner_step_variable(PortState& ps) const {
  // The owner step just ended becomes the one the path reflects; the new one, of substeps_
  // substeps, starts at u_J(T) = ps.u_T at T = ps.T.
  const std::size_t n3 = ps.u_T.size();
  const auto p = static_cast<std::size_t>(substeps_);
  ps.path_prev.swap(ps.path_cur);
  ps.path_prev_t.swap(ps.path_cur_t);
  ps.omega_prev.swap(ps.omega_cur);
  ps.path_cur.resize((p + 1) * n3);
  ps.path_cur_t.assign(p + 1, ps.T);
  std::copy(ps.u_T.begin(), ps.u_T.end(), ps.path_cur.begin());
  if (ps.rotates) ps.omega_cur.resize(p * n3);
}

void LayerStepper::lts_send_forces_variable() {
  // Fbar(T) = (H_prev L(T) + H_next R(T)) / (H_prev + H_next), the one-sided hat averages of the
  // layer's force g on J over the owner step before T and the one after,
  //   L(T) = g(T) / p_prev + sum_q 2 (p_prev - q) / p_prev^2 g(T - q h_prev),
  //   R(T) = g(T) / p_next + sum_q 2 (p_next - q) / p_next^2 g(T + q h_next),
  // weighed by their lengths as the owner's central difference weighs a(T) over
  // (H_prev + H_next) / 2 ([2] with variable steps). At equal steps the fixed form's hat
  // (Diaz & Grote 2009 seen from the coarse side, coupling-study/lts/lts_2proc.py); at t = 0
  // R alone, at the end L alone (one-sided, as fixed). Sent once T + (p_next - 1) h is done.
  const bool start = t_ == 0;
  const bool lands = !start && t_ == owner_T_ + owner_H_;
  const std::int64_t p = substeps_;
  const std::int64_t q = start ? 0 : substep_ + 1;
  const auto pp = static_cast<double>(p * p);
  const double w_right = static_cast<double>(2 * (p - q)) / pp;  // into R(acc_T), 0 < q < p
  const double w_left = static_cast<double>(2 * q) / pp;         // into L(T + H), 0 < q < p
  const double w_end = 1.0 / static_cast<double>(p);             // g(T + H) into L(T + H)
  for (std::size_t pi = 0; pi < ports_.size(); ++pi) {
    const auto& port = ports_[pi];
    if (!port.fine_side) continue;
    auto& ps = state_[pi];
    for (std::size_t j = 0; j < port.local.size(); ++j) {
      const Vec3 g = solver_.net_force(port.local[j]);
      const Vec3 mo = ps.rotates ? solver_.net_moment(port.local[j]) : Vec3{};
      for (std::size_t d = 0; d < 3; ++d) {
        const std::size_t k = 3 * j + d;
        if (start) {
          ps.g_T[k] = g[d];
          if (ps.rotates) ps.m_T[k] = mo[d];
        } else if (!lands) {
          ps.fbar_T[k] += w_right * g[d];
          ps.fbar_T1[k] += w_left * g[d];
          if (ps.rotates) {
            ps.mbar_T[k] += w_right * mo[d];
            ps.mbar_T1[k] += w_left * mo[d];
          }
        } else {
          ps.fbar_T1[k] += w_end * g[d];
          ps.g_T[k] = g[d];
          if (ps.rotates) {
            ps.mbar_T1[k] += w_end * mo[d];
            ps.m_T[k] = mo[d];
          }
        }
      }
    }
    Tick H_next = owner_H_;
    std::int64_t p_next = p;
    bool send = !start && !lands && q == p - 1;
    if (start) {
      ps.acc_T = 0;
      ps.H_prev = 0;
      send = p == 1;
    } else if (lands) {
      if (finished_here()) {  // the last: L alone
        LayerMessage m;
        m.kind = LayerMessage::Kind::Force;
        m.interface_index = port.index;
        m.time = t_;
        m.proposal = proposal_sent_ = proposal_ticks();
        m.first = ps.fbar_T1;
        m.second = ps.mbar_T1;
        lts_send_fbar(ps, std::move(m), owner_H_);
        continue;
      }
      ps.fbar_left.swap(ps.fbar_T1);
      ps.mbar_left.swap(ps.mbar_T1);
      std::fill(ps.fbar_T1.begin(), ps.fbar_T1.end(), 0.0);
      std::fill(ps.fbar_T.begin(), ps.fbar_T.end(), 0.0);
      std::fill(ps.mbar_T1.begin(), ps.mbar_T1.end(), 0.0);
      std::fill(ps.mbar_T.begin(), ps.mbar_T.end(), 0.0);
      ps.H_prev = owner_H_;
      ps.acc_T = t_;
      CRASHLINK_ASSERT(next_owner_known_);
      H_next = next_owner_H_;
      p_next = next_substeps_;
      send = p_next == 1;
    }
    if (!send) continue;
    const double Hp = static_cast<double>(ps.H_prev), Hn = static_cast<double>(H_next);
    const double wl = Hp / (Hp + Hn), wr = Hn / (Hp + Hn), g0 = 1.0 / static_cast<double>(p_next);
    LayerMessage m;
    m.kind = LayerMessage::Kind::Force;
    m.interface_index = port.index;
    m.time = ps.acc_T;
    m.proposal = proposal_sent_ = proposal_ticks();
    m.first.resize(ps.fbar_T.size());
    for (std::size_t k = 0; k < m.first.size(); ++k)
      m.first[k] = wl * ps.fbar_left[k] + wr * (ps.fbar_T[k] + g0 * ps.g_T[k]);
    m.second.resize(ps.mbar_T.size());
    for (std::size_t k = 0; k < m.second.size(); ++k)
      m.second[k] = wl * ps.mbar_left[k] + wr * (ps.mbar_T[k] + g0 * ps.m_T[k]);
    lts_send_fbar(ps, std::move(m), ps.H_prev);
  }
}

void LayerStepper::lts_send_fbar(PortState& ps, LayerMessage m, Tick H_before) {
  // Restored at an owner instant T with p > 1 (layer_stepper_state.cpp): the owner's checkpoint
  // is past Fbar(T) and the coordinator's history has its row; only the meter moves on.
  const bool consumed = ps.consumed == m.time;
  if (consumed) ps.consumed = -1;
  lts_record_row(ps, m, H_before, !consumed);
  if (!consumed) outbox_.push_back(std::move(m));
}

void LayerStepper::lts_record_row(PortState& ps, const LayerMessage& m, Tick H_before, bool keep) {
  // The interface history row at m.time (a daemon's; coupling/layer_work.h): Fbar(T) with u_J(T)
  // and omega_J(T - H/2), received with it (none at t = 0), H the owner step that ended at T.
  if (!record_history_) return;
  ps.meter.set_coarse_step_s(seconds(H_before));
  const auto& uJ = m.time == ps.T ? ps.u_T : ps.u_1;
  const std::span<const double> omega =
      m.time == 0 ? std::span<const double>() : std::span<const double>(ps.omega);
  auto row = ps.meter.add(m.time, m.first, m.second, uJ, omega);
  if (keep) ps.rows.push_back(std::move(row));
}

}  // namespace crashlink::cosim
