#pragma once
// The discrete energy the `lts` scheme conserves (docs/multirate.md "lts"), one domain's share.
//
// Leapfrog local time stepping (Diaz & Grote 2009, SIAM J. Sci. Comput. 31, eq. (3.9)-(3.12) for
// the scheme, Theorem 3.1 for the energy) advances every dof over a coarse step H as
//   u^{n+1} - 2 u^n + u^{n-1} = -H^2 M^-1 K_H u^n,   K_H symmetric,
// and conserves E^{n+1/2} = 1/2 v^T M v + 1/2 u^{n+1 T} K_H u^n, v = (u^{n+1} - u^n) / H, in the
// linear case with no load. K_H is never formed: with K_H u^n = -M (u^{n+1} - 2u^n + u^{n-1}) / H^2
// the energy is a sum over nodes of
//   e_i = m_i / (2 H^2) [ |u_i^{n+1} - u_i^n|^2 - u_i^{n+1} . (u_i^{n+1} - 2 u_i^n + u_i^{n-1}) ]
// from each node's displacements at three coarse instants. Each domain sums the nodes it owns
// (ghosts left out: their owner counts them with their summed mass), and the sum over the domains
// is E. A share alone is not an energy (it can be negative); only the sum is. Held dofs count 0.
// Rotational dofs (shell nodes) add the same with the rotary inertia I_i and the rotation theta_i
// (the sum of the step's increments dt omega^{n+1/2}, small rotations).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/state_archive.h"

namespace crashlink::cosim {

class LtsEnergy {
 public:
  /// `owned[i]` 1 for the nodes this domain integrates (not ghosts), `fixed` the model's DofBits
  /// masks (empty: none held), `mass_kg` and `inertia_kgm2` the integration masses and rotary
  /// inertias, H the coarse step [s].
  void reset(std::vector<std::uint8_t> owned, std::vector<std::uint8_t> fixed,
             std::vector<double> mass_kg, std::vector<double> inertia_kgm2, double coarse_step_s);
  /// After each cycle: theta += dt omega^{n+1/2} [3 n, rad/s] (every dof; only the rotating owned
  /// free ones weigh in the sums).
  void add_rotation(const double* omega_mid, double dt_s);
  /// The displacements u [3 n, m] at coarse instant k (k H; the rotations are add_rotation's).
  /// With `evaluate`, and the two instants before sampled too, value_J() becomes E^{k-1/2} of the
  /// three (ready()); a caller that wants E only at some instants samples just those and the two
  /// before each (a gap starts the count again).
  void sample(const double* u, std::int64_t k, bool evaluate);
  bool ready() const { return ready_; }
  double value_J() const { return value_J_; }  ///< this domain's share of E^{k-1/2} [J]
  void save(core::StateWriter& w, const std::string& prefix) const;
  void restore(const core::StateReader& r, const std::string& prefix);

 private:
  std::vector<double> weight_;      ///< [3 n] m_i of a free dof of an owned node, else 0
  std::vector<double> weight_rot_;  ///< [3 n] I_i alike (inertia > 0), empty if none
  std::vector<double> theta_;       ///< [3 n] rotation so far [rad]
  std::vector<double> u1_, u2_;     ///< u at the previous and the one before [3 n]
  std::vector<double> t1_, t2_;     ///< theta alike [3 n]
  double h2_ = 0.0;                 ///< H^2 [s^2]
  std::int64_t samples_ = 0;        ///< consecutive instants sampled, up to the last
  std::int64_t last_k_ = -1;        ///< the last instant sampled (kAnyNext: take the next)
  bool ready_ = false;              ///< value_J_ is the last sample's E
  double value_J_ = 0.0;
  static constexpr std::int64_t kAnyNext = -2;  ///< restored from a checkpoint without last_k
};

}  // namespace crashlink::cosim
