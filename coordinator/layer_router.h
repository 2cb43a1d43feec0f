#pragma once
// The coordinator's part of the `layer` scheme (DESIGN.md §2.7 "How to distribute layer", §3):
// per interface, the coarse side (owner of J) sends u_J(T + H) and the fine side (holder of the
// moved layer) sends the layer's force g_A(T) on J; the coordinator forwards each to the other
// side in arrival order, checks that every interface's messages come in time order, and keeps the
// interface's history:
//   velocity jump and displacement gap on J: 0 by construction (the ghosts follow the owner);
//   the resultant layer force sum_J g_A(T) [N];
//   the link work W(T + H) = W(T) + 1/2 (g_A(T) + g_A(T + H)) . (u_J(T + H) - u_J(T)) summed over
//   J (trapezoid rule on the owner's instants; u_J(0) = 0) [J], plus for shell J nodes the work
//   of the layer's moment m_A, 1/2 (m_A(T) + m_A(T + H)) . H omega_J(T + H/2) (the owner's
//   rotation increment over the step), as the owner counts its coupling work (Solver).
// Pure logic: no sockets, no solver. Messages are identified by (interface, time in ticks).
//
// Array shapes: every vector [3 n_J], xyz interleaved, in the interface's J order.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "coordinator/ticks.h"

namespace crashlink::coordinator {

struct LayerRoute {
  int fine = -1;               ///< domain holding the layer and the ghosts J (sends forces)
  int coarse = -1;             ///< domain owning J (sends displacements)
  std::size_t n_j = 0;         ///< number of J nodes
  Tick coarse_step = 0;        ///< H: forces at 0, H, 2H, ...; displacements at H, 2H, ...
  double coarse_step_s = 0.0;  ///< H in seconds (the rotation increment H omega)
};

/// One history row of an interface, at an owner instant.
struct LayerSample {
  Tick time = 0;
  double link_work_J = 0.0;
  std::array<double, 3> force_N{};  ///< resultant of g_A over J
};

class LayerRouter {
 public:
  /// `names[k]` is domain k's name (messages). Throws crashlink::ModelError for a route with a
  /// bad domain index, fine == coarse, or a step < 1.
  LayerRouter(std::vector<LayerRoute> routes, std::vector<std::string> names);

  /// Where a message goes, and the history rows it completed (usually 0 or 1).
  struct Routed {
    int to = -1;
    std::vector<LayerSample> samples;
  };

  /// A LayerForce from domain `from`. Throws ProtocolError (coordinator/protocol_error.h) naming
  /// the domain and the values: unknown interface, `from` not its fine side, a time other than
  /// the next expected one, wrong vector sizes.
  Routed force(int from, std::uint32_t interface, Tick time, std::span<const double> force_N,
               std::span<const double> moment_Nm);
  /// A LayerDisplacement from domain `from` (same checks; `from` must be the coarse side).
  Routed displacement(int from, std::uint32_t interface, Tick time,
                      std::span<const double> displacement_m,
                      std::span<const double> angular_velocity_rad_s);

  /// One interface between two owner instants, all it needs to go on (checkpoints, DESIGN.md
  /// §2.6 "Checkpoints"): the next expected times and the vectors of the last history row.
  struct TrackState {
    Tick next_force = 0;
    Tick next_displacement = 0;
    std::vector<double> g_prev, u_prev, m_prev;
    bool have_prev = false;
    double work_J = 0.0;
  };
  /// Interface i right after its force at an owner instant was paired (layer_router_state.cpp).
  /// Throws ModelError if a message is still waiting to be paired (not between two instants).
  TrackState track_state(std::size_t i) const;
  /// A restarted run: interface i continues from `s`; every domain's latest time becomes `time`
  /// and the forwarded count `forwarded`.
  void restore_track(std::size_t i, TrackState s);
  void restore_progress(Tick time, std::int64_t forwarded);

  std::size_t size() const { return routes_.size(); }
  const LayerRoute& route(std::size_t i) const { return routes_[i]; }
  /// Time of the latest message domain k sent on any interface (-1: none yet).
  Tick latest(int k) const { return latest_[static_cast<std::size_t>(k)]; }
  /// Messages forwarded so far.
  std::int64_t forwarded() const { return forwarded_; }

 private:
  struct Track {
    Tick next_force = 0;
    Tick next_displacement = 0;
    struct Vectors {
      Tick time = 0;
      std::vector<double> first;   // g_A or u_J
      std::vector<double> second;  // m_A or omega_J (empty: no rotation)
    };
    std::deque<Vectors> forces;                  // not yet paired
    std::deque<Vectors> displacements;           // not yet paired
    std::vector<double> g_prev, u_prev, m_prev;  // at the last row
    bool have_prev = false;
    double work_J = 0.0;
  };

  const LayerRoute& checked(int from, std::uint32_t interface, bool force_message, Tick time,
                            std::size_t first_size, std::size_t second_size) const;
  std::vector<LayerSample> pair_up(Track& t, const LayerRoute& r);

  std::vector<LayerRoute> routes_;
  std::vector<std::string> names_;
  std::vector<Track> tracks_;
  std::vector<Tick> latest_;
  std::int64_t forwarded_ = 0;
};

}  // namespace crashlink::coordinator
