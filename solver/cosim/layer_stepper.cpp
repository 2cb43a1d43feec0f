// LayerStepper: one domain's side of the `layer` scheme (layer_stepper.h; docs/design.md §2.7).
#include "solver/cosim/layer_stepper.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/errors.h"

namespace crashlink::cosim {

namespace {
const char* kind_name(LayerMessage::Kind k) {
  return k == LayerMessage::Kind::Force ? "layer force" : "layer displacement";
}
}  // namespace

LayerStepper::LayerStepper(integration::Solver& solver, std::vector<LayerPort> ports, Tick step,
                           std::int64_t ticks_per_second, LayerSteps steps)
    : solver_(solver),
      ports_(std::move(ports)),
      h_(step),
      variable_(steps != LayerSteps::Fixed),
      common_(steps == LayerSteps::VariableCommon),
      ticks_per_second_(ticks_per_second) {
  const std::string& dom = solver_.domain_name();
  if (variable_) {
    planned_h_ = h_;  // lts: the first cycle's (set_form)
    h_ = 0;           // chosen at every instant (leader) or owner step (follower)
    std::string owner;
    for (const auto& port : ports_) {
      if (!port.fine_side) continue;
      if (follower_ && port.partner != owner)
        throw ModelError("layer stepper '" + dom + "': variable steps need at most one coarser " +
                         "partner per domain, but this domain holds ghosts of '" + owner +
                         "' and of '" + port.partner +
                         "', whose steps would have to meet; run with fixed steps");
      follower_ = true;
      owner = port.partner;
    }
  }
  if ((!variable_ && h_ < 1) || ticks_per_second_ < 1)  // (variable: h_ is 0 until chosen)
    throw ModelError("layer stepper '" + dom + "': step " + std::to_string(h_) +
                     " ticks and ticks_per_second " + std::to_string(ticks_per_second_) +
                     " must both be >= 1");
  const std::size_t n = solver_.model().nodes.count();
  const auto& gl = solver_.ghost_nodes();
  ghost_slot_.assign(n, kNone);
  for (std::size_t k = 0; k < gl.size(); ++k) ghost_slot_[static_cast<std::size_t>(gl[k])] = k;
  std::vector<std::uint8_t> covered(gl.size(), 0);
  state_.resize(ports_.size());
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    auto& ps = state_[p];
    for (auto l : port.local) {
      if (l >= n)
        throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                         " names local node " + std::to_string(l) + " of " + std::to_string(n));
      const bool ghost = ghost_slot_[l] != kNone;
      if (ghost != port.fine_side)
        throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                         ": node id " + std::to_string(solver_.model().nodes.id[l]) + " is " +
                         (ghost ? "a ghost" : "not a ghost") + " but this domain is its " +
                         (port.fine_side ? "fine (ghost) side" : "coarse (owner) side"));
      if (ghost) {
        if (covered[ghost_slot_[l]]++)
          throw ModelError("layer stepper '" + dom + "': ghost node id " +
                           std::to_string(solver_.model().nodes.id[l]) +
                           " belongs to two interfaces");
      }
      ps.rotates = ps.rotates || solver_.inertia()[l] > 0.0;
    }
    if (port.fine_side && !variable_) {
      ps.meter = coupling::LayerWorkMeter(seconds(port.partner_step));
      if (port.partner_step < h_ || port.partner_step % h_ != 0)
        throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                         ": the owner's step " + std::to_string(port.partner_step) +
                         " ticks is not a whole multiple of this domain's step " +
                         std::to_string(h_) +
                         " ticks; the fine side must land on every coarse instant (nested steps, "
                         "coupling/nested_steps.h)");
    }
  }
  for (std::size_t k = 0; k < gl.size(); ++k)
    if (!covered[k])
      throw ModelError("layer stepper '" + dom + "': ghost node id " +
                       std::to_string(solver_.model().nodes.id[static_cast<std::size_t>(gl[k])]) +
                       " belongs to no interface");
  ghost_u_.assign(3 * gl.size(), 0.0);
  ghost_omega_.assign(3 * gl.size(), 0.0);
  end_ = to_ticks_end(solver_.model().controls.end_time_s);
}

void LayerStepper::set_end_time(Tick end) {
  if (end < 0 || variable_)
    throw ModelError(
        fmt::format("layer stepper '{}': set_end_time({}) is for fixed steps and a "
                    "time >= 0",
                    solver_.domain_name(), end));
  end_ = end;
}

Tick LayerStepper::to_ticks_end(double t_s) const {
  // The end instant, rounded to the nearest tick (a run ends at its first instant >= it).
  const double x = t_s * static_cast<double>(ticks_per_second_);
  if (!(x >= 0.0) || x > 4.0e18)
    throw ModelError("layer stepper '" + solver_.domain_name() + "': end time " +
                     std::to_string(t_s) + " s is not representable in ticks");
  return static_cast<Tick>(std::nearbyint(x));
}

double LayerStepper::seconds(Tick n) const {
  return static_cast<double>(n) / static_cast<double>(ticks_per_second_);
}

void LayerStepper::initialize() {
  if (phase_ != Phase::Initial || initialized_)
    throw ModelError("layer stepper '" + solver_.domain_name() + "': initialize() called twice");
  initialized_ = true;
  if (!variable_) impose_fixed_step();
  step_pending_ = variable_ && follower_;  // a leader chooses once the g_A(0) are in
  t_ = 0;
  if (lts_variable()) {  // the first owner step is the plan's (set_form checked it)
    h_ = announced_ = planned_h_;
    step_pending_ = false;
    for (const auto& port : ports_)
      if (port.fine_side) owner_H_ = port.partner_step;
    owner_T_ = 0;
    substeps_ = owner_H_ > 0 ? owner_H_ / h_ : 1;
    substep_ = 0;
    solver_.impose_step(seconds(h_));
  }
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    auto& ps = state_[p];
    const std::size_t n3 = 3 * port.local.size();
    if (port.fine_side) {
      ps.T = 0;
      ps.u_T.assign(n3, 0.0);
      for (std::size_t j = 0; j < port.local.size(); ++j)
        for (std::size_t d = 0; d < 3; ++d)
          ps.u_T[3 * j + d] = solver_.displacement()[3 * port.local[j] + d];
      ps.have_u1 = false;
      ps.T1 = 0;
      // the owner's first message: u_J(H); with variable steps any later instant
      ps.next_expected = variable_ ? 1 : port.partner_step;
      if (form_ == LayerForm::Lts) lts_start_port(port, ps);
    } else {
      ps.next_expected = 0;  // the holder's g_A(0)
      // u_J(t + h) leaves before the ghosts' motion is applied (Phase::Positions), so the J
      // nodes this domain owns must not be ghosts of another port.
      const auto& ghosts = solver_.ghost_nodes();
      for (const std::size_t i : port.local)
        if (std::find(ghosts.begin(), ghosts.end(), static_cast<std::int32_t>(i)) != ghosts.end())
          throw ModelError(fmt::format(
              "layer stepper '{}': interface {}: node id {} is a J node this domain owns and a "
              "ghost of another interface; cut the model so that the interfaces do not touch",
              solver_.domain_name(), port.index, solver_.model().nodes.id[i]));
    }
  }
  if (form_ == LayerForm::Lts && !variable_) lts_start_energy();
  if (!forces_wait_for_holders()) send_forces();  // g_A(0) of every fine port (else: Initial)
}

void LayerStepper::deliver(LayerMessage m) {
  const std::string& dom = solver_.domain_name();
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    if (ports_[p].index != m.interface_index) continue;
    const auto& port = ports_[p];
    auto& ps = state_[p];
    const auto want = port.fine_side ? LayerMessage::Kind::Displacement : LayerMessage::Kind::Force;
    if (m.kind != want)
      throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                       ": got a " + kind_name(m.kind) + " from '" + port.partner +
                       "', expected a " + kind_name(want));
    // After a restore, a partner sends again what this side had received before its checkpoint
    // (used, or kept in the checkpoint's inbox): instants before the one the checkpoint expects.
    // Dropped and counted (repeats_dropped), the first ones only; in process a pause leaves the
    // domains at different instants (LayerNetwork::run), the daemons' checkpoints are at one.
    if (ps.drop_before >= 0) {
      if (m.time < ps.drop_before) {
        ++repeats_dropped_;
        return;
      }
      ps.drop_before = -1;
    }
    if (variable_ ? m.time < ps.next_expected : m.time != ps.next_expected)
      throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                       ": " + kind_name(m.kind) + " from '" + port.partner + "' for t = " +
                       std::to_string(m.time) + " ticks, expected t " + (variable_ ? ">= " : "= ") +
                       std::to_string(ps.next_expected) + " ticks (out of order or duplicated)");
    const std::size_t n3 = 3 * port.local.size();
    if (m.first.size() != n3 || !(m.second.empty() || m.second.size() == n3))
      throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                       ": " + kind_name(m.kind) + " from '" + port.partner + "' carries " +
                       std::to_string(m.first.size()) + " + " + std::to_string(m.second.size()) +
                       " values; expected " + std::to_string(n3) + " (3 per J node)");
    if (variable_ && m.kind == LayerMessage::Kind::Force && m.proposal < 0)
      throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                       ": layer force from '" + port.partner + "' with the step proposal " +
                       std::to_string(m.proposal) + " ticks; expected >= 0 (0: no limit)");
    if (variable_) {  // the next one is later; its instant is not known here
      if (m.time == std::numeric_limits<Tick>::max())
        throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                         ": " + kind_name(m.kind) + " for the last representable tick");
      ps.next_expected = m.time + 1;
      ps.inbox.push_back(std::move(m));
      return;
    }
    const Tick every = port.fine_side ? port.partner_step : h_;
    if (ps.next_expected > std::numeric_limits<Tick>::max() - every)
      throw ModelError("layer stepper '" + dom + "': interface " + std::to_string(port.index) +
                       ": " + kind_name(m.kind) + " from '" + port.partner + "' for t = " +
                       std::to_string(m.time) + " ticks; the next one, " + std::to_string(every) +
                       " ticks later, would be beyond the tick range (2^63 - 1 ticks): the "
                       "coordinator's steps do not fit this run (a smaller ticks_per_second)");
    ps.next_expected += every;
    ps.inbox.push_back(std::move(m));
    return;
  }
  throw ModelError("layer stepper '" + dom + "': " + kind_name(m.kind) + " for interface " +
                   std::to_string(m.interface_index) + ", which this domain is not part of");
}

std::vector<LayerRows> LayerStepper::take_history() {
  std::vector<LayerRows> out;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    auto& ps = state_[p];
    if (ps.rows.empty()) continue;
    out.push_back({ports_[p].index, std::exchange(ps.rows, {})});
  }
  return out;
}

std::deque<LayerMessage> LayerStepper::take_outbox() {
  return std::exchange(outbox_, {});
}

void LayerStepper::flush_outbox() {
  if (on_outbox_ && !outbox_.empty()) on_outbox_();
}

bool LayerStepper::ghost_targets_ready() {
  // Every fine port: J at t + h, linear in time between the owner's u_J(T) and u_J(T+H)
  // (LRunner of coupling-study/layer-check: Unext = uJ_T + (t1 - T)/H (uJ_1 - uJ_T)).
  const Tick t1 = t_ + h_;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (!port.fine_side) continue;
    auto& ps = state_[p];
    if (variable_) {
      if (ps.have_u1 && t_ == ps.T1) {  // moved on to the next owner step
        ps.u_T.swap(ps.u_1);
        ps.T = ps.T1;
        ps.have_u1 = false;
        if (form_ == LayerForm::Lts) lts_next_owner_step_variable(ps);
      }
    } else {
      const Tick H = port.partner_step;
      const Tick T = (t_ / H) * H;
      if (T != ps.T) {  // moved on to the next owner step
        CRASHLINK_ASSERT(T == ps.T + H && ps.have_u1);
        ps.u_T.swap(ps.u_1);
        ps.T = T;
        ps.have_u1 = false;
        if (form_ == LayerForm::Lts) lts_next_owner_step(ps);
      }
    }
    // Lts: the owner's u_J(T + H) is needed only by the substep that lands on it.
    const Tick lands_at = lts_variable() ? owner_T_ + owner_H_ : ps.T + port.partner_step;
    const bool need_u1 = form_ != LayerForm::Lts || t1 == lands_at;
    if (!ps.have_u1 && need_u1) {
      if (ps.inbox.empty()) {
        wait_iface_ = port.index;
        return false;
      }
      auto& m = ps.inbox.front();
      CRASHLINK_ASSERT(variable_ || m.time == ps.T + port.partner_step);
      if (lts_variable() && m.time != lands_at)
        throw LayerPartnerError(fmt::format(
            "layer stepper '{}': interface {}: the owner '{}' sent u_J for t = {} ticks, but "
            "the owner step [{}, {}] ticks it announced ends at {} ticks (lts, variable steps)",
            solver_.domain_name(), port.index, port.partner, m.time, owner_T_, lands_at, lands_at));
      ps.next_step_1 = m.next_step;
      ps.last_1 = m.last;
      ps.pause_1 = m.pause;
      ps.T1 = m.time;
      ps.u_1 = std::move(m.first);
      ps.omega = std::move(m.second);
      ps.inbox.pop_front();
      ps.have_u1 = true;
    }
  }
  // Lts, variable: the landing substep knows the owner step after it (its u_J says it)
  if (lts_variable() && t1 == owner_T_ + owner_H_) {
    [[maybe_unused]] const bool known = lts_decide_next_owner_step();
    CRASHLINK_ASSERT(known);
  }
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (!port.fine_side) continue;
    const auto& ps = state_[p];
    const Tick H = lts_variable() ? owner_H_ : variable_ ? ps.T1 - ps.T : port.partner_step;
    if (t1 > ps.T + H)
      throw ModelError(
          fmt::format("layer stepper '{}': interface {}: the step to t = {} ticks "
                      "passes the owner's instant {} ticks (internal error)",
                      solver_.domain_name(), port.index, t1, ps.T + H));
    if (form_ == LayerForm::Lts) {
      lts_ghost_targets(port, state_[p], t1);
      continue;
    }
    const bool lands = t1 == ps.T + H;
    const double w = static_cast<double>(t1 - ps.T) / static_cast<double>(H);
    for (std::size_t j = 0; j < port.local.size(); ++j) {
      const std::size_t s = ghost_slot_[port.local[j]];
      for (std::size_t d = 0; d < 3; ++d) {
        const std::size_t i = 3 * j + d;
        // exactly the owner's u(T+H) when landing: at H = h this is the split cycle to the bit
        ghost_u_[3 * s + d] = lands ? ps.u_1[i] : ps.u_T[i] + w * (ps.u_1[i] - ps.u_T[i]);
        ghost_omega_[3 * s + d] = ps.omega.empty() ? 0.0 : ps.omega[i];  // omega_J(T + H/2)
      }
    }
  }
  return true;
}

void LayerStepper::send_displacements() {
  // Coarse ports: u_J(t + h) and omega_J(t + h/2), known once the positions are updated; or, if
  // sent ahead (send_displacements_ahead), checked against them.
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (port.fine_side) continue;
    auto& ps = state_[p];
    if (ps.sent_ahead == t_ + h_) {
      for (std::size_t j = 0; j < port.local.size(); ++j)
        for (std::size_t d = 0; d < 3; ++d) {
          const std::size_t k = 3 * port.local[j] + d;
          const double u = solver_.displacement()[k];
          const double w = solver_.angular_velocity_mid()[k];
          const double su = ps.ahead_u[3 * j + d];
          const double sw = ps.ahead_omega.empty() ? w : ps.ahead_omega[3 * j + d];
          const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
          if (bits(u) != bits(su) || bits(w) != bits(sw))
            throw std::logic_error(fmt::format(
                "layer stepper '{}': interface {}: node id {} dof {}: the u_J / omega_J sent "
                "ahead to '{}' ({:.17g} m, {:.17g} rad/s) differ from the nodal passes' ({:.17g} "
                "m, {:.17g} rad/s) at t = {} ticks; Solver::predict_next_positions no longer "
                "mirrors them",
                solver_.domain_name(), port.index, solver_.model().nodes.id[port.local[j]], d,
                port.partner, su, sw, u, w, t_ + h_));
        }
      continue;
    }
    ++displacements_sent_;
    LayerMessage m = displacement_message(port);
    m.first.resize(3 * port.local.size());
    if (state_[p].rotates) m.second.resize(3 * port.local.size());
    for (std::size_t j = 0; j < port.local.size(); ++j)
      for (std::size_t d = 0; d < 3; ++d) {
        m.first[3 * j + d] = solver_.displacement()[3 * port.local[j] + d];
        if (!m.second.empty())
          m.second[3 * j + d] = solver_.angular_velocity_mid()[3 * port.local[j] + d];
      }
    outbox_.push_back(std::move(m));
  }
}

LayerMessage LayerStepper::displacement_message(const LayerPort& port) const {
  // u_J(t + h) of a coarse port, vectors left to the caller
  LayerMessage m;
  m.kind = LayerMessage::Kind::Displacement;
  m.interface_index = port.index;
  m.time = t_ + h_;
  m.last = variable_ && finishes_at(m.time);
  m.pause = variable_ && pauses_at(m.time);
  if (lts_variable()) m.next_step = m.last ? 0 : announced_;
  return m;
}

void LayerStepper::send_displacements_ahead() {
  // After the coupling loads at t (apply_forces), before end_cycle_accelerations(): u_J(t + h)
  // and omega_J(t + h/2) as the next cycle's passes will make them (Solver::
  // predict_next_positions), unless the run ends at t (finished_here(): no next cycle).
  if (finished_here() || pausing_now()) return;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (port.fine_side) continue;
    auto& ps = state_[p];
    const std::size_t n3 = 3 * port.local.size();
    ps.ahead_u.resize(n3);
    ps.ahead_omega.resize(ps.rotates ? n3 : 0);
    if (!solver_.predict_next_positions(port.local, seconds(h_), ps.ahead_u.data(),
                                        ps.rotates ? ps.ahead_omega.data() : nullptr))
      continue;  // sent after the passes (send_displacements)
    ps.sent_ahead = t_ + h_;
    ++displacements_sent_;
    ++displacements_ahead_;
    LayerMessage m = displacement_message(port);
    m.first = ps.ahead_u;
    m.second = ps.ahead_omega;
    outbox_.push_back(std::move(m));
  }
}

void LayerStepper::send_forces() {
  // Fine ports at an owner instant: the layer's force (and moment) on J, g_A(t) ([8]).
  if (form_ == LayerForm::Lts) {
    lts_send_forces();  // every fine instant: the hat average (layer_stepper_lts.cpp)
    return;
  }
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    const auto& port = ports_[p];
    if (!port.fine_side || !at_owner_instant(port)) continue;
    LayerMessage m;
    m.kind = LayerMessage::Kind::Force;
    m.interface_index = port.index;
    m.time = t_;
    if (variable_) m.proposal = proposal_sent_ = common_ ? subtree_proposal() : proposal_ticks();
    m.first.resize(3 * port.local.size());
    if (state_[p].rotates) m.second.resize(3 * port.local.size());
    for (std::size_t j = 0; j < port.local.size(); ++j) {
      const Vec3 f = solver_.net_force(port.local[j]);
      const Vec3 mo = m.second.empty() ? Vec3{} : solver_.net_moment(port.local[j]);
      for (std::size_t d = 0; d < 3; ++d) {
        m.first[3 * j + d] = f[d];
        if (!m.second.empty()) m.second[3 * j + d] = mo[d];
      }
    }
    if (record_history_) {
      // u_J(T): 0 at T = 0 (the owner's initial displacement), else the target of the owner step
      // [T - H, T] just completed, with omega_J(T - H/2) (ghost_targets_ready).
      auto& ps = state_[p];
      const bool start = t_ == 0;
      if (variable_ && !start) ps.meter.set_coarse_step_s(seconds(ps.T1 - ps.T));
      const std::span<const double> omega =
          start ? std::span<const double>() : std::span<const double>(ps.omega);
      ps.rows.push_back(ps.meter.add(t_, m.first, m.second, start ? ps.u_T : ps.u_1, omega));
    }
    outbox_.push_back(std::move(m));
  }
}

bool LayerStepper::forces_ready() {
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    if (ports_[p].fine_side) continue;
    const auto& ps = state_[p];
    if (ps.inbox.empty()) {
      wait_iface_ = ports_[p].index;
      return false;
    }
    if (variable_ && ps.inbox.front().time != t_)
      throw LayerPartnerError(fmt::format(
          "layer stepper '{}': interface {}: layer force from '{}' for "
          "t = {} ticks, but this domain is at {} ticks",
          solver_.domain_name(), ports_[p].index, ports_[p].partner, ps.inbox.front().time, t_));
    CRASHLINK_ASSERT(ps.inbox.front().time == t_);
  }
  return true;
}

void LayerStepper::apply_initial_forces() {
  // t = 0: Solver::initialize() computed a^0 with this domain's forces only; the holders' forces
  // on J complete it (exchange_initial_forces' rule: a^0 += g_A(0) / M_J, the implied force is
  // counted as coupling work over the first step).
  const std::size_t n = solver_.model().nodes.count();
  std::vector<double> df;
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    if (ports_[p].fine_side) continue;
    auto& ps = state_[p];
    const auto m = std::move(ps.inbox.front());
    ps.inbox.pop_front();
    if (df.empty()) df.assign(3 * n, 0.0);
    for (std::size_t j = 0; j < ports_[p].local.size(); ++j)
      for (std::size_t d = 0; d < 3; ++d) df[3 * ports_[p].local[j] + d] += m.first[3 * j + d];
  }
  if (df.empty()) return;
  const auto& fixed = solver_.model().fixed;
  for (std::size_t i = 0; i < n; ++i) {
    const double* f = &df[3 * i];
    if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) continue;
    Vec3 a{};
    for (std::size_t d = 0; d < 3; ++d) {
      a[d] = solver_.acceleration()[3 * i + d] + f[d] / solver_.mass()[i];
      if (!fixed.empty() && (fixed[i] & (1u << d))) a[d] = 0.0;
    }
    solver_.set_acceleration(i, a);
  }
}

void LayerStepper::apply_forces() {
  // [8]: a_J = (g_B + g_A) / M_J, g_A added between the solver's two halves.
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    if (ports_[p].fine_side) continue;
    auto& ps = state_[p];
    const auto m = std::move(ps.inbox.front());
    ps.inbox.pop_front();
    solver_.add_coupling_loads(ports_[p].local, m.first.data(),
                               m.second.empty() ? nullptr : m.second.data());
  }
}

void LayerStepper::impose_fixed_step() {
  try {
    solver_.impose_step(seconds(h_));
  } catch (const NumericalError& e) {
    throw NumericalError(fmt::format(
        "{}. Fixed `layer` steps are planned once, from --step-safety x the initial stable steps, "
        "and this domain's stable step is now below its fixed one: run with --variable-steps "
        "(every domain then follows its own stable step), or with a smaller --step-safety",
        e.what()));
  }
}

LayerStepper::Wait LayerStepper::advance(const std::function<void()>& on_sample, Tick until) {
  if (!initialized_)
    throw ModelError("layer stepper '" + solver_.domain_name() +
                     "': advance() before initialize()");
  until_ = until;
  for (;;) {
    switch (phase_) {
      case Phase::Initial:
        if (!forces_ready()) return wait_ = Wait::Force;
        if (forces_wait_for_holders()) {  // g_A(0) with the holders' proposals at 0
          send_forces();
          flush_outbox();
        }
        if (lts_variable()) {  // the plan's first step; announced_: the one after
          Tick next = 0;
          if (!lts_plan_next(next)) return wait_ = Wait::Displacement;
          CRASHLINK_ASSERT(next == h_);
        } else if (variable_ && !follower_) {
          h_ = choose_step();  // reads the g_A(0) proposals
        }
        apply_initial_forces();
        if (variable_ && !follower_ && !lts_variable()) solver_.impose_step(seconds(h_));
        phase_ = Phase::Begin;
        break;
      case Phase::Begin:
        if (pause_here()) return wait_ = Wait::None;
        if (step_pending_) {  // a variable follower at the end of its owner step
          if (finished_here()) {
            if (h_ > 0) solver_.impose_committed_step(seconds(h_));  // for the last sample
          } else {
            if (!start_owner_step()) return wait_ = Wait::Displacement;
            solver_.impose_step(seconds(h_));  // from the proposal sent with g_A(t)
          }
          step_pending_ = false;
        }
        solver_.begin_cycle();  // state at t_ complete
        if (form_ == LayerForm::Lts && !variable_ && t_ % energy_period_ == 0) lts_sample_energy();
        if (on_sample) on_sample();
        if (finished_here()) {
          phase_ = Phase::Done;
          return wait_ = Wait::Finished;
        }
        phase_ = Phase::Positions;
        break;
      case Phase::Positions:
        solver_.end_cycle_positions();  // the ghosts' (J of the fine ports) left provisional
        send_displacements();
        flush_outbox();  // u_J(t + h) leaves before this domain's forces
        // Overlap (docs/design.md §2.6): the elements that touch no ghost need nothing from the
        // owners, so a fine domain computes them before it waits for u_J(t + h).
        solver_.end_cycle_interior_forces();
        phase_ = Phase::Rim;
        break;
      case Phase::Rim:
        if (!ghost_targets_ready()) return wait_ = Wait::Displacement;
        if (!ghost_u_.empty()) {
          solver_.set_ghost_displacement(ghost_u_.data());
          solver_.set_ghost_angular_velocity(ghost_omega_.data());
        }
        if (form_ == LayerForm::Lts)  // plastic flow on the rim at the owner instants only
          solver_.set_rim_returns(!lts_owner_instant(t_), !lts_owner_instant(t_ + h_));
        solver_.end_cycle_compute();  // overlaps the partners' work
        if (form_ == LayerForm::Lts && !variable_)
          lts_energy_.add_rotation(solver_.angular_velocity_mid().data(), seconds(h_));
        t_ += h_;
        if (!forces_wait_for_holders()) {
          send_forces();
          flush_outbox();
        }
        phase_ = Phase::Accelerations;
        break;
      case Phase::Accelerations:
        if (!forces_ready()) return wait_ = Wait::Force;
        if (forces_wait_for_holders()) {  // g_A(t) with the holders' proposals at t
          send_forces();
          flush_outbox();
        }
        {
          // The next step: fixed; a leader's choice (reads the g_A proposals, before
          // apply_forces takes them); a follower's next substep, or unknown at the end of its
          // owner step (step_pending_: the owner's next u_J tells it).
          Tick next = h_;
          if (lts_variable()) {
            if (!lts_plan_next(next)) return wait_ = Wait::Displacement;
          } else if (variable_) {
            if (!follower_) {
              next = choose_step();
            } else if (at_owner_end()) {
              next = 0;
            } else {
              ++substep_;
              next = next_substep();
            }
          }
          apply_forces();
          if (next > 0) {
            h_ = next;
            send_displacements_ahead();
            flush_outbox();  // u_J(t + h) leaves before this domain's nodal passes
          }
          solver_.end_cycle_accelerations();
          if (next == 0)
            step_pending_ = true;
          else if (variable_ && (follower_ || lts_variable()))  // lts: chosen an instant ago
            solver_.impose_committed_step(seconds(h_));
          else if (variable_)
            solver_.impose_step(seconds(h_));
          else
            impose_fixed_step();
        }
        phase_ = Phase::Begin;
        break;
      case Phase::Done:
        return wait_ = Wait::Finished;
    }
  }
}

}  // namespace crashlink::cosim
