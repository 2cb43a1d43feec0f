#pragma once
// The coordinator's part of the `layer` scheme when it routes the layer vectors (docs/design.md
// §2.7 "How to distribute layer", §3; without lanes, docs/processes.md "Lanes"): per interface, the
// coarse side (owner of J) sends u_J(T + H) and the fine side (holder of the moved layer) sends
// the layer's force g_A(T) on J; the coordinator forwards each to the other side in arrival
// order and checks that every interface's messages come in time order from the right side with
// the right sizes. The interface histories come from the fine side's LayerReports
// (layer_work.h), whether the vectors go through the coordinator or daemon to daemon.
// Pure logic: no sockets, no solver. Messages are identified by (interface, time in ticks).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "coupling/layer_work.h"
#include "coupling/ticks.h"

namespace crashlink::coupling {

struct LayerRoute {
  int fine = -1;               ///< domain holding the layer and the ghosts J (sends forces)
  int coarse = -1;             ///< domain owning J (sends displacements)
  std::size_t n_j = 0;         ///< number of J nodes
  Tick coarse_step = 0;        ///< H: forces at 0, H, 2H, ...; displacements at H, 2H, ...
  double coarse_step_s = 0.0;  ///< H in seconds (the rotation increment H omega)
};

class LayerRouter {
 public:
  /// `names[k]` is domain k's name (messages). Throws crashlink::ModelError for a route with a
  /// bad domain index, fine == coarse, or a step < 1.
  LayerRouter(std::vector<LayerRoute> routes, std::vector<std::string> names);
  /// Variable steps (cosim::LayerSteps::Variable): every interface's vectors and rows only in
  /// increasing time order, any instants (coarse_step is then the first planned one, unused).
  /// Call before any message.
  void set_variable_steps(bool on);

  /// Where a message goes.
  struct Routed {
    int to = -1;
  };

  /// A LayerForce from domain `from`. Throws ProtocolError (core/errors.h) naming
  /// the domain and the values: unknown interface, `from` not its fine side, a time other than
  /// the next expected one, wrong vector sizes.
  Routed force(int from, std::uint32_t interface, Tick time, std::span<const double> force_N,
               std::span<const double> moment_Nm);
  /// A LayerDisplacement from domain `from` (same checks; `from` must be the coarse side).
  Routed displacement(int from, std::uint32_t interface, Tick time,
                      std::span<const double> displacement_m,
                      std::span<const double> angular_velocity_rad_s);

  /// History rows of `interface` from domain `from`'s LayerReport: `times` [n] owner instants,
  /// `force_N` [3 n] resultant layer forces, `work_J` [n] link works. Throws ProtocolError naming
  /// the domain and the values: unknown interface, `from` not its fine side, sizes that do not
  /// match, a time other than the next row's (consecutive multiples of H from 0).
  std::vector<LayerSample> rows(int from, std::uint32_t interface,
                                std::span<const std::int64_t> times,
                                std::span<const double> force_N, std::span<const double> work_J);

  /// A restarted run from the checkpoint at T (an instant of every domain): every interface
  /// expects its next force, displacement and history row at T + H (variable steps: after T); the
  /// forwarded count becomes `forwarded`.
  void restore_progress(Tick time, std::int64_t forwarded);

  std::size_t size() const { return routes_.size(); }
  const LayerRoute& route(std::size_t i) const { return routes_[i]; }
  /// Messages forwarded so far.
  std::int64_t forwarded() const { return forwarded_; }
  /// Messages of every interface for the instants up to T (an instant of every domain), whoever
  /// routed them: fixed steps, its forces g_A(0), g_A(H), ..., g_A(T) and displacements u_J(H),
  /// ..., u_J(T), i.e. sum over interfaces of 2 T/H + 1; variable steps, those this router
  /// forwarded up to T (it keeps the instants of each interface's latest kRecent). A checkpoint
  /// at T counts what the coordinator forwarded with min(forwarded(), this): vectors for later
  /// instants sent before it (a faster partner's, or a coarse side's u_J(T + H), sent ahead) are
  /// sent again after a restart. Variable steps: std::logic_error when a vector after T has
  /// already been folded into the count (more than kRecent of an interface's vectors after T).
  std::int64_t messages_through(Tick time) const;
  static constexpr std::size_t kRecent = 64;

 private:
  struct Track {
    Tick next_force = 0;
    Tick next_displacement = 0;
    Tick next_row = 0;
  };

  const LayerRoute& checked(int from, std::uint32_t interface, bool force_message, Tick time,
                            std::size_t first_size, std::size_t second_size) const;
  /// The least spacing of an interface's instants: its coarse step, or 1 tick with variable steps
  /// (any later instant).
  Tick spacing(const LayerRoute& r) const { return variable_ ? 1 : r.coarse_step; }
  /// Variable steps: a forwarded vector of interface i at `time` (messages_through's window).
  void remember(std::uint32_t i, Tick time);

  std::vector<LayerRoute> routes_;
  std::vector<std::string> names_;
  std::vector<Track> tracks_;
  std::int64_t forwarded_ = 0;
  std::vector<std::deque<Tick>> recent_;  ///< variable: [interfaces] latest forwarded instants
  std::int64_t folded_ = 0;               ///< variable: forwarded vectors out of recent_
  Tick folded_latest_ = -1;               ///< variable: the latest instant among them
  bool variable_ = false;
};

}  // namespace crashlink::coupling
