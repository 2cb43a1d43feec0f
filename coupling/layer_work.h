#pragma once
// The history of one `layer` interface (docs/design.md §2.7 "How to distribute layer"), computed
// where both vectors of an owner instant T are known, on the fine side: the layer's force g_A(T) on
// J (and its moment m_A(T) on shell J nodes), which it computes, and u_J(T) (and omega_J(T - H/2)),
// which it received from the owner. Rows:
//   velocity jump and displacement gap on J: 0 by construction (the ghosts follow the owner);
//   the resultant layer force sum_J g_A(T) [N];
//   the link work W(T) = W(T - H) + 1/2 (g_A(T - H) + g_A(T)) . (u_J(T) - u_J(T - H)) summed over
//   J (trapezoid rule on the owner's instants; u_J(0) = 0) [J], plus for shell J nodes the work of
//   the layer's moment, 1/2 (m_A(T - H) + m_A(T)) . H omega_J(T - H/2) (the owner's rotation
//   increment over the step), as the owner counts its coupling work (Solver).
// Pure arithmetic: no sockets, no solver. Every vector [3 n_J], xyz interleaved, J order.
#include <array>
#include <span>
#include <vector>

#include "coupling/ticks.h"

namespace crashlink::coupling {

/// One history row of an interface, at an owner instant.
struct LayerSample {
  Tick time = 0;
  double link_work_J = 0.0;
  std::array<double, 3> force_N{};  ///< resultant of g_A over J
};

/// All a meter needs to go on after the row at its last instant (checkpoints).
struct LayerWorkState {
  std::vector<double> g_prev, u_prev, m_prev;  ///< at the last row
  bool have_prev = false;
  double work_J = 0.0;
};

class LayerWorkMeter {
 public:
  /// `coarse_step_s`: the owner's step H [s] (the rotation increment H omega).
  explicit LayerWorkMeter(double coarse_step_s = 0.0) : H_s_(coarse_step_s) {}

  /// The row at owner instant T (called at T = 0, H, 2H, ... in order). `m` and `omega` are
  /// empty when no J node rotates.
  LayerSample add(Tick T, std::span<const double> g, std::span<const double> m,
                  std::span<const double> u, std::span<const double> omega);

  /// The owner step of the next row, for variable steps (H of the row at T + H).
  void set_coarse_step_s(double coarse_step_s) { H_s_ = coarse_step_s; }
  const LayerWorkState& state() const { return s_; }
  void restore(LayerWorkState s) { s_ = std::move(s); }

 private:
  double H_s_ = 0.0;
  LayerWorkState s_;
};

}  // namespace crashlink::coupling
