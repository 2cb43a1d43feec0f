#include "coordinator/layer_router.h"

#include <fmt/format.h>

#include <limits>

#include "coordinator/protocol_error.h"
#include "solver/core/errors.h"

namespace crashlink::coordinator {

LayerRouter::LayerRouter(std::vector<LayerRoute> routes, std::vector<std::string> names)
    : routes_(std::move(routes)), names_(std::move(names)) {
  const int n = static_cast<int>(names_.size());
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    const auto& r = routes_[i];
    if (r.fine < 0 || r.fine >= n || r.coarse < 0 || r.coarse >= n || r.fine == r.coarse ||
        r.coarse_step < 1) {
      throw ModelError(
          fmt::format("layer router: interface {} joins domains {} and {} of {} "
                      "with a coarse step of {} ticks; need two different domains "
                      "and a step >= 1",
                      i, r.fine, r.coarse, n, r.coarse_step));
    }
  }
  tracks_.resize(routes_.size());
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    tracks_[i].next_displacement = routes_[i].coarse_step;
    // u_J(0) = 0: the first row (T = 0) needs only g_A(0).
    tracks_[i].displacements.push_back({0, std::vector<double>(3 * routes_[i].n_j, 0.0), {}});
  }
  latest_.assign(names_.size(), -1);
}

const LayerRoute& LayerRouter::checked(int from, std::uint32_t interface, bool force_message,
                                       Tick time, std::size_t first_size,
                                       std::size_t second_size) const {
  const char* what = force_message ? "LayerForce" : "LayerDisplacement";
  const std::string who = from >= 0 && from < static_cast<int>(names_.size())
                              ? names_[static_cast<std::size_t>(from)]
                              : fmt::format("#{}", from);
  if (interface >= routes_.size()) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {}; the scenario has {} "
                    "interfaces",
                    who, what, interface, routes_.size()));
  }
  const auto& r = routes_[interface];
  const int sender = force_message ? r.fine : r.coarse;
  if (from != sender) {
    throw ProtocolError(fmt::format(
        "domain '{}' sent a {} for interface {}, which only its {} side '{}' sends", who, what,
        interface, force_message ? "fine" : "coarse", names_[static_cast<std::size_t>(sender)]));
  }
  const auto& t = tracks_[interface];
  const Tick expected = force_message ? t.next_force : t.next_displacement;
  if (time != expected) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {} at {} ticks; the next "
                    "one must be at {} ticks (every {} ticks, in time order)",
                    who, what, interface, time, expected, r.coarse_step));
  }
  if (time > std::numeric_limits<Tick>::max() - r.coarse_step) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {} at {} ticks; the one after it, {} "
                    "ticks later, would be beyond the tick range (2^63 - 1 ticks): the "
                    "coordinator's steps do not fit this run (a smaller ticks_per_second)",
                    who, what, interface, time, r.coarse_step));
  }
  const std::size_t n = 3 * r.n_j;
  if (first_size != n || (second_size != 0 && second_size != n)) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {} at {} ticks with "
                    "vectors of {} and {} values; expected {} (3 x {} J nodes) "
                    "and {} or 0",
                    who, what, interface, time, first_size, second_size, n, r.n_j, n));
  }
  return r;
}

LayerRouter::Routed LayerRouter::force(int from, std::uint32_t interface, Tick time,
                                       std::span<const double> force_N,
                                       std::span<const double> moment_Nm) {
  const auto& r = checked(from, interface, true, time, force_N.size(), moment_Nm.size());
  auto& t = tracks_[interface];
  t.next_force = time + r.coarse_step;
  t.forces.push_back({time, std::vector<double>(force_N.begin(), force_N.end()),
                      std::vector<double>(moment_Nm.begin(), moment_Nm.end())});
  latest_[static_cast<std::size_t>(from)] = std::max(latest_[static_cast<std::size_t>(from)], time);
  ++forwarded_;
  return {r.coarse, pair_up(t, r)};
}

LayerRouter::Routed LayerRouter::displacement(int from, std::uint32_t interface, Tick time,
                                              std::span<const double> displacement_m,
                                              std::span<const double> angular_velocity_rad_s) {
  const auto& r =
      checked(from, interface, false, time, displacement_m.size(), angular_velocity_rad_s.size());
  auto& t = tracks_[interface];
  t.next_displacement = time + r.coarse_step;
  t.displacements.push_back(
      {time, std::vector<double>(displacement_m.begin(), displacement_m.end()),
       std::vector<double>(angular_velocity_rad_s.begin(), angular_velocity_rad_s.end())});
  // u_J(T + H) is known once the owner is at T + H minus its compute: count it at T.
  latest_[static_cast<std::size_t>(from)] =
      std::max(latest_[static_cast<std::size_t>(from)], time - r.coarse_step);
  ++forwarded_;
  return {r.fine, pair_up(t, r)};
}

std::vector<LayerSample> LayerRouter::pair_up(Track& t, const LayerRoute& r) {
  std::vector<LayerSample> out;
  while (!t.forces.empty() && !t.displacements.empty() &&
         t.forces.front().time == t.displacements.front().time) {
    auto f = std::move(t.forces.front());
    auto d = std::move(t.displacements.front());
    t.forces.pop_front();
    t.displacements.pop_front();
    const auto& g = f.first;
    const auto& u = d.first;
    if (t.have_prev) {
      // Trapezoid rule on [T_prev, T]: 1/2 (g(T_prev) + g(T)) . (u(T) - u(T_prev)).
      double dw = 0.0;
      for (std::size_t i = 0; i < g.size(); ++i) {
        dw += 0.5 * (t.g_prev[i] + g[i]) * (u[i] - t.u_prev[i]);
      }
      // Moments: 1/2 (m(T_prev) + m(T)) . H omega(T_prev + H/2), as Solver counts them.
      const auto& m = f.second;
      const auto& omega = d.second;
      if (!m.empty() && !omega.empty()) {
        for (std::size_t i = 0; i < m.size(); ++i) {
          const double m_prev = t.m_prev.empty() ? 0.0 : t.m_prev[i];
          dw += 0.5 * m_prev * (r.coarse_step_s * omega[i]);
          dw += 0.5 * m[i] * (r.coarse_step_s * omega[i]);
        }
      }
      t.work_J += dw;
    }
    LayerSample s;
    s.time = f.time;
    s.link_work_J = t.work_J;
    for (std::size_t i = 0; i < g.size(); ++i) s.force_N[i % 3] += g[i];
    out.push_back(s);
    t.g_prev = std::move(f.first);  // the vectors are not needed any more: no copies
    t.u_prev = std::move(d.first);
    t.m_prev = std::move(f.second);
    t.have_prev = true;
  }
  return out;
}

}  // namespace crashlink::coordinator
