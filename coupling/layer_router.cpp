#include "coupling/layer_router.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "core/errors.h"

namespace crashlink::coupling {

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
  recent_.resize(routes_.size());
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    tracks_[i].next_displacement = routes_[i].coarse_step;  // u_J(H) first; g_A(0) first
  }
}

void LayerRouter::set_variable_steps(bool on) {
  variable_ = on;
  for (std::size_t i = 0; i < routes_.size(); ++i)
    tracks_[i].next_displacement = on ? 1 : routes_[i].coarse_step;  // u_J after 0
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
  if (variable_ && time < expected) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {} at {} ticks; the next one must be "
                    "at {} ticks or later (in time order)",
                    who, what, interface, time, expected));
  }
  if (!variable_ && time != expected) {
    throw ProtocolError(
        fmt::format("domain '{}' sent a {} for interface {} at {} ticks; the next "
                    "one must be at {} ticks (every {} ticks, in time order; variable steps: "
                    "any later instant)",
                    who, what, interface, time, expected, r.coarse_step));
  }
  if (time > std::numeric_limits<Tick>::max() - spacing(r)) {
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
  tracks_[interface].next_force = time + spacing(r);
  ++forwarded_;
  remember(interface, time);
  return {r.coarse};
}

LayerRouter::Routed LayerRouter::displacement(int from, std::uint32_t interface, Tick time,
                                              std::span<const double> displacement_m,
                                              std::span<const double> angular_velocity_rad_s) {
  const auto& r =
      checked(from, interface, false, time, displacement_m.size(), angular_velocity_rad_s.size());
  tracks_[interface].next_displacement = time + spacing(r);
  ++forwarded_;
  remember(interface, time);
  return {r.fine};
}

std::vector<LayerSample> LayerRouter::rows(int from, std::uint32_t interface,
                                           std::span<const std::int64_t> times,
                                           std::span<const double> force_N,
                                           std::span<const double> work_J) {
  const std::string who = from >= 0 && from < static_cast<int>(names_.size())
                              ? names_[static_cast<std::size_t>(from)]
                              : fmt::format("#{}", from);
  if (interface >= routes_.size() || routes_[interface].fine != from) {
    throw ProtocolError(fmt::format(
        "domain '{}' reported history rows of interface {}, {}", who, interface,
        interface >= routes_.size() ? fmt::format("one of {} interfaces", routes_.size())
                                    : std::string("of which it is not the fine side")));
  }
  const std::size_t n = times.size();
  if (force_N.size() != 3 * n || work_J.size() != n) {
    throw ProtocolError(
        fmt::format("domain '{}' reported {} history rows of interface {} with {} "
                    "force values and {} link works; expected {} and {}",
                    who, n, interface, force_N.size(), work_J.size(), 3 * n, n));
  }
  const Tick every = spacing(routes_[interface]);
  auto& t = tracks_[interface];
  std::vector<LayerSample> out(n);
  for (std::size_t r = 0; r < n; ++r) {
    if ((variable_ ? times[r] < t.next_row : times[r] != t.next_row) ||
        times[r] > std::numeric_limits<Tick>::max() - every) {
      throw ProtocolError(fmt::format(
          "domain '{}' reported a history row of interface {} at {} ticks; the next one must be "
          "at {} ticks{} (in time order, within the tick range)",
          who, interface, times[r], t.next_row, variable_ ? " or later" : ""));
    }
    t.next_row = times[r] + every;
    out[r].time = times[r];
    out[r].link_work_J = work_J[r];
    for (std::size_t d = 0; d < 3; ++d) out[r].force_N[d] = force_N[3 * r + d];
  }
  return out;
}

void LayerRouter::remember(std::uint32_t i, Tick time) {
  if (!variable_) return;
  auto& q = recent_[i];
  q.push_back(time);
  if (q.size() <= kRecent) return;
  folded_latest_ = std::max(folded_latest_, q.front());
  ++folded_;
  q.pop_front();
}

std::int64_t LayerRouter::messages_through(Tick time) const {
  std::int64_t n = 0;
  if (!variable_) {
    for (const auto& r : routes_) n += 2 * (time / r.coarse_step) + 1;
    return n;
  }
  if (folded_latest_ > time)
    throw std::logic_error(
        fmt::format("layer router: the vectors forwarded up to {} ticks are asked for after one "
                    "at {} ticks was folded into the count (more than {} of an interface's "
                    "vectors after it)",
                    time, folded_latest_, kRecent));
  n = folded_;
  for (const auto& q : recent_)
    n += std::count_if(q.begin(), q.end(), [&](Tick t) { return t <= time; });
  return n;
}

void LayerRouter::restore_progress(Tick time, std::int64_t forwarded) {
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    const Tick next = time + spacing(routes_[i]);
    tracks_[i].next_force = next;
    tracks_[i].next_displacement = next;
    tracks_[i].next_row = next;
    recent_[i].clear();
  }
  forwarded_ = forwarded;
  folded_ = forwarded;
  folded_latest_ = time;
}

}  // namespace crashlink::coupling
