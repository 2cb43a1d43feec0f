// The coordinator's `paper` exchange (paper_exchange.h).
#include "coordinator/paper_exchange.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <span>
#include <string>

#include "core/errors.h"
#include "coupling/interpolation.h"

namespace crashlink::coordinator {

namespace paper = coupling::paper;
using coupling::Tick;

namespace {

std::vector<std::pair<int, int>> partner_pairs(const LayerCut& cut) {
  std::vector<std::pair<int, int>> p;
  for (const auto& c : cut.interfaces)
    p.emplace_back(std::min(c.fine, c.coarse), std::max(c.fine, c.coarse));
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

double distance3(const double* a, const double* b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

void gather(const std::vector<double>& from, const std::vector<std::size_t>& nodes,
            std::vector<double>& to) {
  to.resize(3 * nodes.size());
  for (std::size_t j = 0; j < nodes.size(); ++j)
    for (std::size_t d = 0; d < 3; ++d) to[3 * j + d] = from[3 * nodes[j] + d];
}

void scatter(const std::vector<double>& from, const std::vector<std::size_t>& nodes,
             std::vector<double>& to) {
  for (std::size_t j = 0; j < nodes.size(); ++j)
    for (std::size_t d = 0; d < 3; ++d) to[3 * nodes[j] + d] = from[3 * j + d];
}

}  // namespace

Tick paper_end_ticks(double end_time_s, const std::vector<Tick>& steps, std::int64_t tps) {
  const auto end = static_cast<Tick>(std::llround(end_time_s * static_cast<double>(tps)));
  Tick period = 1;
  for (const Tick h : steps) {
    if (h <= 0) continue;
    // lcm(period, h) = period / gcd * h: check before it can overflow.
    const Tick g = std::gcd(period, h);
    if (period / g > (Tick{1} << 60) / h)
      throw ModelError(fmt::format(
          "paper: the domains' fixed steps ({} ticks) have no common multiple below 2^60 ticks, "
          "where every domain would land at the end; fix: --variable-steps, or steps that nest "
          "(--mode multi plans them so)",
          fmt::join(steps, ", ")));
    period = period / g * h;
  }

  return (end + period - 1) / period * period;
}

PaperExchange::PaperExchange(const PaperCut& cut, const coupling::InterfaceTable& table,
                             std::vector<Tick> steps, paper::Drift drift, double guard_rise,
                             std::int64_t ticks_per_second, Steps policy)
    : cut_(cut),
      steps_(std::move(steps)),
      policy_(policy),
      drift_(drift),
      tps_(ticks_per_second),
      schedule_(
          static_cast<int>(cut.cut.names.size()), partner_pairs(cut.cut),
          policy == Steps::variable_common ? coupling::StepPolicy::common
                                           : coupling::StepPolicy::own,
          policy == Steps::fixed
              ? paper_end_ticks(cut.cut.end_time_s, steps_, tps_)
              : static_cast<Tick>(std::llround(cut.cut.end_time_s * static_cast<double>(tps_))),
          policy != Steps::variable_common),
      domains_(cut.cut.names.size()),
      interfaces_(cut.cut.interfaces.size()),
      guard_(guard_rise) {
  if (steps_.size() != domains_.size() || table.node_of.size() != domains_.size())
    throw ModelError(
        fmt::format("paper exchange: {} steps and {} registered domains for {} domains",
                    steps_.size(), table.node_of.size(), domains_.size()));
  for (std::size_t k = 0; k < domains_.size(); ++k) {
    auto& D = domains_[k];
    const auto& nodes = cut.nodes[k];
    D.n = nodes.size();
    D.mass_kg = table.summed_masses(static_cast<int>(k));
    D.ref.resize(D.n);
    D.interface.resize(D.n);
    for (std::size_t i = 0; i < D.n; ++i) {
      D.ref[i] = nodes[i].reference ? 1 : 0;
      D.interface[i] = nodes[i].interface;
      const auto& node = table.nodes[static_cast<std::size_t>(table.node_of[k][i])];
      const auto& other =
          node.copies[0].domain == static_cast<int>(k) ? node.copies[1] : node.copies[0];
      auto g = std::find_if(D.groups.begin(), D.groups.end(),
                            [&](const Group& x) { return x.partner == other.domain; });
      if (g == D.groups.end()) g = D.groups.insert(D.groups.end(), Group{other.domain, {}, {}});
      g->mine.push_back(i);
      g->theirs.push_back(static_cast<std::size_t>(other.local));
    }
    for (auto& s : D.slot) {
      s.a.assign(3 * D.n, 0.0);
      s.u.assign(3 * D.n, 0.0);
      s.v.assign(3 * D.n, 0.0);
    }
    D.f_link.assign(3 * D.n, 0.0);
    D.f_drift.assign(3 * D.n, 0.0);
    D.u_last.assign(3 * D.n, 0.0);
  }
  for (std::size_t i = 0; i < interfaces_.size(); ++i) {
    auto& I = interfaces_[i];
    I.fine = cut.cut.interfaces[i].fine;
    I.coarse = cut.cut.interfaces[i].coarse;
    const auto& F = domains_[static_cast<std::size_t>(I.fine)];
    for (const auto& g : F.groups) {
      if (g.partner != I.coarse) continue;
      for (std::size_t j = 0; j < g.mine.size(); ++j)
        if (F.interface[g.mine[j]] == i) I.pairs.emplace_back(g.mine[j], g.theirs[j]);
    }
  }
}

double PaperExchange::seconds(Tick t) const {
  return static_cast<double>(t) / static_cast<double>(tps_);
}

void PaperExchange::unstable(Tick t, const std::string& what) const {
  std::string steps;
  for (std::size_t k = 0; k < domains_.size(); ++k)
    steps +=
        fmt::format("{}{} {:.4e} s", k == 0 ? "" : ", ", cut_.cut.names[k], seconds(steps_[k]));
  const auto [lo, hi] = std::minmax_element(steps_.begin(), steps_.end());
  throw NumericalError(paper::unstable_message(
      fmt::format("at t = {:.6e} s", seconds(t)), what, drift_,
      fmt::format("{:.4g} ({}: {})",
                  *lo > 0 ? static_cast<double>(*hi) / static_cast<double>(*lo) : 0.0,
                  policy_ == Steps::fixed ? "steps" : "variable steps, initially", steps)));
}

void PaperExchange::submit(int k, const wire::FreeState& s) {
  auto& D = domains_[static_cast<std::size_t>(k)];
  const auto& name = cut_.cut.names[static_cast<std::size_t>(k)];
  const auto n3 = static_cast<int>(3 * D.n);
  if (s.accelerations_m_s2_size() != n3 || s.displacements_m_size() != n3 ||
      s.velocities_m_s_size() != n3)
    throw ProtocolError(fmt::format(
        "domain '{}' sent a free state at tick {} with {} accelerations, {} displacements and {} "
        "velocities; its {} coupled nodes need {} of each",
        name, s.time_ticks(), s.accelerations_m_s2_size(), s.displacements_m_size(),
        s.velocities_m_s_size(), D.n, n3));
  // The energies of the previous instant first (cosim::PaperRunner samples them before it reads
  // the next free state), each state's exactly once: its previous state's instant, -1 first.
  const Tick expected_energy = D.submitted == 0 ? -1 : D.latest;
  if (s.energy_time_ticks() != expected_energy)
    throw ProtocolError(fmt::format(
        "domain '{}' sent, with its free state at tick {}, energies of tick {}; expected those of "
        "its previous state (tick {}; -1 with the first)",
        name, s.time_ticks(), s.energy_time_ticks(), expected_energy));
  if (expected_energy >= 0) {
    D.energy[expected_energy] = s.energy();
    check_energies();
  }
  for (int i = 0; i < n3; ++i)
    if (!std::isfinite(s.accelerations_m_s2(i)))
      unstable(
          s.time_ticks(),
          fmt::format("the free acceleration of coupled node id {} in domain '{}' is {} "
                      "(nothing was sent back)",
                      cut_.node_ids[static_cast<std::size_t>(k)][static_cast<std::size_t>(i / 3)],
                      name, s.accelerations_m_s2(i)));
  const Tick plan = steps_[static_cast<std::size_t>(k)];
  const Tick step =
      policy_ == Steps::fixed || s.stable_step_ticks() < 1 ? plan : s.stable_step_ticks();
  const int slot = schedule_.submit(k, s.time_ticks(), step);
  auto& S = D.slot[slot];
  S.time = s.time_ticks();
  S.a.assign(s.accelerations_m_s2().begin(), s.accelerations_m_s2().end());
  S.u.assign(s.displacements_m().begin(), s.displacements_m().end());
  S.v.assign(s.velocities_m_s().begin(), s.velocities_m_s().end());
  D.latest = s.time_ticks();
  ++D.submitted;
}

void PaperExchange::final_energy(int k, const wire::EnergyTerms& e, Tick time) {
  auto& D = domains_[static_cast<std::size_t>(k)];
  if (time != D.latest)
    throw ProtocolError(
        fmt::format("domain '{}' ended with the energies of tick {}; its last state is at tick {}",
                    cut_.cut.names[static_cast<std::size_t>(k)], time, D.latest));
  D.energy[time] = e;
  check_energies();
}

void PaperExchange::check_energies() {
  // Instants every domain has reported its energy at, oldest first; variable multi steps rarely
  // share one: there, each domain's latest energy, once the oldest of them has advanced.
  for (;;) {
    Tick T = -1;
    if (policy_ == Steps::variable_own) {
      Tick oldest = -1;
      for (const auto& D : domains_) {
        if (D.energy.empty()) return;
        const Tick t = D.energy.rbegin()->first;
        oldest = oldest < 0 ? t : std::min(oldest, t);
      }
      if (oldest <= guard_time_) return;
      guard_time_ = oldest;
      T = oldest;
    } else {
      auto& first = domains_.front().energy;
      auto it = std::find_if(first.begin(), first.end(), [&](const auto& e) {
        return std::all_of(domains_.begin(), domains_.end(),
                           [&](const Domain& D) { return D.energy.count(e.first) != 0; });
      });
      if (it == first.end()) return;
      T = it->first;
    }
    double total = 0.0, external = 0.0, work = 0.0, twice = 0.0;
    for (auto& D : domains_) {
      const auto e = policy_ == Steps::variable_own ? D.energy.rbegin()->second : D.energy.at(T);
      total += e.kinetic_j() + e.internal_j() + e.hourglass_j() + e.contact_j();
      external += e.external_work_j();
      work += e.coupling_work_j();
      twice += e.coupled_kinetic_j();
      if (policy_ == Steps::variable_own) {
        D.energy.erase(D.energy.begin(), std::prev(D.energy.end()));  // keep the latest
      } else {
        D.energy.erase(D.energy.begin(), D.energy.upper_bound(T));
      }
    }
    total -= twice;
    if (!have_initial_) {
      have_initial_ = true;
      initial_J_ = total;
      twice0_J_ = twice;
    }
    if (auto why = guard_.sample(total - external, total, initial_J_ + external))
      unstable(T, fmt::format("{}; net work of the link and drift corrections {:.4e} J", *why,
                              work - (twice - twice0_J_)));
    if (policy_ == Steps::variable_own) return;
  }
}

std::optional<std::pair<int, wire::Envelope>> PaperExchange::next() {
  const auto ans = schedule_.pop();
  if (!ans) return std::nullopt;
  const int k = ans->domain;
  auto& D = domains_[static_cast<std::size_t>(k)];
  const Slot& own = D.slot[ans->slot];
  const std::size_t n3 = 3 * D.n;
  a_link_.assign(n3, 0.0);
  u_ref_.assign(n3, 0.0);
  for (const auto& g : D.groups) {
    const auto b = std::find_if(ans->partners.begin(), ans->partners.end(),
                                [&](const coupling::Bracket& x) { return x.partner == g.partner; });
    CRASHLINK_ASSERT(b != ans->partners.end());
    const auto& L = domains_[static_cast<std::size_t>(g.partner)];
    // [9] with [10] (at a common instant the weight is 0/1: [8], a_own + a_partner, bit for bit).
    gather(own.a, g.mine, own_);
    gather(L.slot[b->lower_slot].a, g.theirs, lo_);
    gather(L.slot[b->upper_slot].a, g.theirs, hi_);
    out_.resize(own_.size());
    paper::multiscale_acceleration(own_, lo_, hi_, b->weight, out_);
    scatter(out_, g.mine, a_link_);
    // [11]'s u_ref: the partner's displacement at t by [10].
    gather(L.slot[b->lower_slot].u, g.theirs, ulo_);
    gather(L.slot[b->upper_slot].u, g.theirs, uhi_);
    uref_g_.resize(ulo_.size());
    coupling::interpolate(ulo_, uhi_, b->weight, uref_g_);
    scatter(uref_g_, g.mine, u_ref_);
  }
  for (std::size_t i = 0; i < D.n; ++i)
    if (D.ref[i])  // the reference side gets no drift correction: u_ref = own u
      for (std::size_t d = 0; d < 3; ++d) u_ref_[3 * i + d] = own.u[3 * i + d];
  // [11] with the step about to be taken. At the end time there is none: the link alone ([8],
  // the single-domain acceleration), as cosim::PaperRunner leaves its last instant.
  da_.assign(n3, 0.0);
  if (!ans->stop)
    paper::drift_correction(
        u_ref_, own.u, paper::drift_step_product(seconds(ans->imposed_step), seconds(D.prev_step)),
        drift_, da_);
  a_star_.resize(n3);
  paper::add_drift(a_link_, da_, a_star_);
  for (std::size_t i = 0; i < n3; ++i)
    if (!std::isfinite(a_star_[i]))
      unstable(ans->time,
               fmt::format("the corrected acceleration of coupled node id {} in domain '{}' is {} "
                           "(nothing was sent)",
                           cut_.node_ids[static_cast<std::size_t>(k)][i / 3],
                           cut_.cut.names[static_cast<std::size_t>(k)], a_star_[i]));

  // Work of the link and drift forces on this presence (trapezoid rule, as the Solver counts).
  for (auto& I : interfaces_)
    if (I.coarse == k) I.force_N = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < D.n; ++i) {
    auto& I = interfaces_[D.interface[i]];
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t j = 3 * i + d;
      const double fl = D.mass_kg[i] * (a_link_[j] - own.a[j]);
      const double fd = D.mass_kg[i] * da_[j];
      const double du = own.u[j] - D.u_last[j];
      I.link_J += 0.5 * (D.f_link[j] + fl) * du;
      I.drift_J += 0.5 * (D.f_drift[j] + fd) * du;
      D.f_link[j] = fl;
      D.f_drift[j] = fd;
      D.u_last[j] = own.u[j];
      if (I.coarse == k) I.force_N[d] += fl;
    }
  }
  if (ans->imposed_step > 0) D.prev_step = ans->imposed_step;
  D.answered = ans->time;
  add_rows(k, ans->time);

  wire::Envelope e;
  auto* c = e.mutable_correction();
  c->set_time_ticks(ans->time);
  c->mutable_accelerations_m_s2()->Add(a_star_.begin(), a_star_.end());
  c->set_imposed_step_ticks(ans->imposed_step);
  c->set_imposed_step_s(seconds(ans->imposed_step));
  c->set_stop(ans->stop);
  return std::make_pair(k, std::move(e));
}

void PaperExchange::add_rows(int k, Tick t) {
  for (std::size_t i = 0; i < interfaces_.size(); ++i) {
    auto& I = interfaces_[i];
    if (I.fine != k && I.coarse != k) continue;
    const auto& F = domains_[static_cast<std::size_t>(I.fine)];
    const auto& C = domains_[static_cast<std::size_t>(I.coarse)];
    if (F.answered != t || C.answered != t || I.row_time == t) continue;
    const auto slot_at = [t](const Domain& D) -> const Slot* {
      for (const auto& s : D.slot)
        if (s.time == t) return &s;
      return nullptr;
    };
    const Slot* sf = slot_at(F);
    const Slot* sc = slot_at(C);
    if (sf == nullptr || sc == nullptr) continue;
    PaperRow r;
    r.interface = static_cast<std::uint32_t>(i);
    r.time = t;
    for (const auto& [f, c] : I.pairs) {
      r.displacement_gap_m =
          std::max(r.displacement_gap_m, distance3(&sf->u[3 * f], &sc->u[3 * c]));
      r.velocity_jump_m_s = std::max(r.velocity_jump_m_s, distance3(&sf->v[3 * f], &sc->v[3 * c]));
    }
    r.link_work_J = I.link_J;
    r.drift_work_J = I.drift_J;
    r.force_N = I.force_N;
    I.row_time = t;
    rows_.push_back(r);
  }
}

std::vector<PaperRow> PaperExchange::take_rows() {
  std::vector<PaperRow> out;
  out.swap(rows_);
  return out;
}

}  // namespace crashlink::coordinator
