// The solver's passes over the nodes (solver.h): velocities and kinetic energy, displacements and
// positions with the work terms, accelerations. Memory-bound: each is one pass per tile of nodes,
// and arrays known to be zero stay out of them (docs/benchmarks.md "Fewer bytes per node-cycle").
#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/integration/central_difference.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

namespace {

/// The nodal arrays of Solver::compute_accelerations.
struct AccelerationArrays {
  const double *f_ext, *f_cont, *f_coup, *f_int, *m_coup, *m_int, *inv_mass, *inv_inertia;
  double *a, *alpha;
  std::size_t n;
};

/// One pass over the nodes: a = (f - f_int) / m with the driving load f = f_ext + f_cont + f_coup
/// ([1], lumped mass; inv_mass 0 for rigid, ghost and massless nodes) and the rotational
/// alpha = (m_coup - m_int) / I. Memory-bound (bench/bench_cycle.cpp), so the arrays known to be
/// zero are not read: f_ext without gravity or loads (kExt false), and f_cont, f_coup and m_coup
/// everywhere (contact_node_pass and coupling_pass redo the few nodes that carry them). Adding an
/// exact zero changes no value (f_cont is never -0: it starts at +0 and sums), so the results are
/// those of the full expression.
template <bool kExt, bool kTurn>
void acceleration_pass(const AccelerationArrays& s, std::size_t i0, std::size_t i1) {
  const double* __restrict fe = s.f_ext;
  const double* __restrict fi = s.f_int;
  const double* __restrict mi = s.m_int;
  const double* __restrict wm = s.inv_mass;
  const double* __restrict wi = s.inv_inertia;
  double* __restrict a = s.a;
  double* __restrict al = s.alpha;
  for (std::size_t i = i0; i < i1; ++i) {
    const double w = wm[i], wr = wi[i];
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
      double f = 0.0;  // f_cont off the contact nodes
      if constexpr (kExt) f = fe[k] + f;
      a[k] = (f - fi[k]) * w;
      if constexpr (kTurn) al[k] = -mi[k] * wr;  // else zero and left so
    }
  }
}

/// acceleration_pass's translational expression with f_cont, at the nodes the contacts pushed.
template <bool kExt>
void contact_node_pass(const AccelerationArrays& s, const std::vector<std::int32_t>& nodes) {
  for (const auto node : nodes) {
    const auto i = static_cast<std::size_t>(node);
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
      double f = s.f_cont[k];
      if constexpr (kExt) f = s.f_ext[k] + f;
      s.a[k] = (f - s.f_int[k]) * s.inv_mass[i];
    }
  }
}

/// acceleration_pass's full expressions at the nodes that carry coupling loads.
void coupling_pass(const AccelerationArrays& s, const std::vector<std::int32_t>& nodes) {
  for (const auto node : nodes) {
    const auto i = static_cast<std::size_t>(node);
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
      const double f = s.f_ext[k] + s.f_cont[k] + s.f_coup[k];
      s.a[k] = (f - s.f_int[k]) * s.inv_mass[i];
      s.alpha[k] = (s.m_coup[k] - s.m_int[k]) * s.inv_inertia[i];
    }
  }
}

/// The F^n half of the external work (Solver::positions_and_work) over dofs [k0, k1) in one pass
/// with x = x0 + u; f_ext skipped when it is zero, as in acceleration_pass. The contact forces'
/// half is summed over their nodes alone (increment_dot).
template <bool kExt>
void positions_pass(const double* __restrict x0, const double* __restrict u,
                    const double* __restrict du, const double* __restrict fe, double* __restrict x,
                    std::size_t k0, std::size_t k1, double& external) {
  double ext = 0.0;  // in index order
  for (std::size_t k = k0; k < k1; ++k) {
    x[k] = x0[k] + u[k];
    if constexpr (kExt) ext += fe[k] * du[k];
  }
  external = ext;
}

/// [2] and positions_pass in one pass over dofs [k0, k1): du = dt v, u += dt v, dtheta = dt omega
/// (advance_displacement's expressions), x = x0 + u and the F^n half of the external work, on one
/// tile. Memory-bound: u and du are not read back from memory by a second pass over all nodes.
/// kStore false (Solver::increment_tile_): du and dtheta are not stored, and the work takes
/// f (dt v), the same product rounded alike.
template <bool kExt, bool kTurn, bool kStore>
double displacement_pass(double* __restrict u, double* __restrict du, double* __restrict dtheta,
                         const double* __restrict v, const double* __restrict omega,
                         const double* __restrict x0, const double* __restrict fe,
                         double* __restrict x, double dt, std::size_t k0, std::size_t k1) {
  for (std::size_t k = k0; k < k1; ++k) {
    if constexpr (kStore) du[k] = dt * v[k];
#ifdef __FMA__
    const double uk = std::fma(dt, v[k], u[k]);  // advance_displacement's rounding
#else
    const double uk = u[k] + dt * v[k];
#endif
    u[k] = uk;
    if constexpr (kTurn && kStore) dtheta[k] = dt * omega[k];  // else zero and left so
    x[k] = x0[k] + uk;
  }
  // apart, so that the loop above vectorises; du (or v) is still in L1 (a tile)
  double ext = 0.0;  // in index order, as positions_pass
  if constexpr (kExt) {
    for (std::size_t k = k0; k < k1; ++k) {
      const double d = kStore ? du[k] : dt * v[k];
      ext += fe[k] * d;
    }
  }
  return ext;
}

/// What kinetic_tile reads: v, w at n+1/2, vp, wp at n-1/2, and the nodes' masses and flags.
struct KineticArrays {
  const double *v, *vp, *w, *wp, *mass, *inertia;
  const std::uint8_t *rigid, *ghost;
};

/// sum + m v^{n-1/2} . v^{n+1/2} (+ I omega^{n-1/2} . omega^{n+1/2} when kTurn) over nodes
/// [i0, i1) in node order; kCheck: leave out rigid and ghost nodes (a tile that has none needs
/// no test).
template <bool kCheck, bool kTurn>
double kinetic_tile(const KineticArrays& a, std::size_t i0, std::size_t i1, double sum) {
  const double* __restrict v = a.v;
  const double* __restrict vp = a.vp;
  const double* __restrict w = a.w;
  const double* __restrict wp = a.wp;
  for (std::size_t i = i0; i < i1; ++i) {
    if constexpr (kCheck)
      if (a.rigid[i] || a.ghost[i]) continue;
    const std::size_t k = 3 * i;
    const double tr = vp[k] * v[k] + vp[k + 1] * v[k + 1] + vp[k + 2] * v[k + 2];
    if constexpr (kTurn) {
      const double rot = wp[k] * w[k] + wp[k + 1] * w[k + 1] + wp[k + 2] * w[k + 2];
      sum += a.mass[i] * tr + a.inertia[i] * rot;
    } else {
      // + 0.0 for the I rot term: m tr is rounded before the sum takes it, as above (without it
      // the compiler fuses m tr into the sum, one rounding fewer: other bits)
      sum += a.mass[i] * tr + 0.0;
    }
  }
  return sum;
}

}  // namespace

void Solver::compute_accelerations() {
  const AccelerationArrays arrays{f_ext_.data(),
                                  f_cont_.data(),
                                  f_coup_.data(),
                                  f_int_.data(),
                                  m_coup_.data(),
                                  m_int_.data(),
                                  inv_mass_.data(),
                                  inv_inertia_.data(),
                                  a_.data(),
                                  alpha_.data(),
                                  n_};
  on_node_ranges([&](std::size_t i0, std::size_t i1) {
    for (std::size_t b = i0; b < i1; b += kNodeTile) {
      const std::size_t e = std::min(i1, b + kNodeTile);
      if (turning(b))
        external_loads_ ? acceleration_pass<true, true>(arrays, b, e)
                        : acceleration_pass<false, true>(arrays, b, e);
      else
        external_loads_ ? acceleration_pass<true, false>(arrays, b, e)
                        : acceleration_pass<false, false>(arrays, b, e);
    }
  });
  if (external_loads_)
    contact_node_pass<true>(arrays, contact_nodes_.nodes());
  else
    contact_node_pass<false>(arrays, contact_nodes_.nodes());
  coupling_pass(arrays, coupled_.nodes());
  const NodalLoads loads{f_ext_.data(), f_cont_.data(), f_coup_.data(),
                         f_int_.data(), m_coup_.data(), m_int_.data()};
  for (auto& b : bodies_)
    if (!b.failed) gather_rigid_load(b, loads, x_.data(), model_.controls.gravity_m_s2);
  check_spot_welds();
  on_node_ranges(
      [&](std::size_t i0, std::size_t i1) { zero_held_tiles(a_.data(), alpha_.data(), i0, i1); });
}

double Solver::kinetic_energy() const {
  // KE^n = 1/2 sum m v^{n-1/2} . v^{n+1/2} (see energy.h), per node tile and then over tiles in
  // order, as velocity_pass sums it: the same bits on either path and for every thread count.
  double sum = 0.0;
  for (std::size_t b = 0; b < n_; b += kNodeTile)
    sum += kinetic_sum(b, std::min(n_, b + kNodeTile), 0.0);
  return kinetic_energy_from(sum);
}

double Solver::kinetic_sum(std::size_t i0, std::size_t i1, double sum) const {
  return kinetic_sum(v_.data(), v_prev_.data(), omega_.data(), omega_prev_.data(), i0, i1, sum);
}

double Solver::kinetic_sum(const double* __restrict v, const double* __restrict vp,
                           const double* __restrict w, const double* __restrict wp, std::size_t i0,
                           std::size_t i1, double sum) const {
  const KineticArrays arrays{
      v, vp, w, wp, mass_.data(), inertia_.data(), rigid_node_.data(), ghost_.data()};
  // a tile without rigid or ghost nodes skips the two tests per node (the same sum)
  const bool check = plain_tile_.empty() || !plain_tile_[i0 / kNodeTile];
  if (!turning(i0))  // omega and I are zero on the tile
    return check ? kinetic_tile<true, false>(arrays, i0, i1, sum)
                 : kinetic_tile<false, false>(arrays, i0, i1, sum);
  return check ? kinetic_tile<true, true>(arrays, i0, i1, sum)
               : kinetic_tile<false, true>(arrays, i0, i1, sum);
}

double Solver::kinetic_energy_from(double node_sum) const {
  double ke = 0.5 * node_sum;
  for (const auto& b : bodies_)
    if (!b.failed) ke += rigid_kinetic_energy(b);
  return ke;
}

double Solver::velocity_pass(double dt_mid) {
  // Per tile of nodes (in L1 for the second and third loops): v^{n+1/2} = v^{n-1/2} +
  // dt^{n-1/2} a^n ([2]) (omega alike; vectorised) written over v^{n-3/2} in v_prev_'s buffer,
  // held dofs zeroed, then m v^{n-1/2} . v^{n+1/2} + I omega^{n-1/2} . omega^{n+1/2} summed in
  // node order over the nodes kinetic_energy() counts, per tile, the tiles' sums then in tile
  // order (the same bits for every thread count; docs/threads.md). The buffers are swapped
  // after the pass: v_ is v^{n+1/2}, v_prev_ v^{n-1/2}, with no copy of v (a memmove of 3.1 % of
  // the 2.5 mm scale run's time, perf, 2026-11-29). Non-turning tiles keep omega zero in both
  // buffers. Nothing keeps v_.data() across a cycle (velocity_mid() is the vector itself).
  // advance_velocity_into per field and tile: its restrict parameters let it vectorise, which a
  // loop through this lambda's captures did not (scalar, dt reloaded per dof: with the kinetic
  // sum, 1.9x the samples, perf of bench_cycle head_impact, 2026-11-28). Same expression, same
  // bits.
  const double* v = v_.data();
  double* vn = v_prev_.data();
  const double* w = omega_.data();
  double* wn = omega_prev_.data();
  const double* a = a_.data();
  const double* al = alpha_.data();
  const double sum = sum_over_tiles([=, this](std::size_t i0, std::size_t i1) {
    const std::size_t k0 = 3 * i0, len = 3 * (i1 - i0);
    advance_velocity_into(vn + k0, v + k0, a + k0, dt_mid, len);
    if (turning(i0)) advance_velocity_into(wn + k0, w + k0, al + k0, dt_mid, len);
    zero_held_tiles(vn, wn, i0, i1);
    return kinetic_sum(vn, v, wn, w, i0, i1, 0.0);
  });
  v_.swap(v_prev_);
  omega_.swap(omega_prev_);
  return sum;
}

void Solver::advance_positions(double dt) {
  // A tile without a rigid body's node takes x^{n+1} = x0 + u^{n+1} and its F^n half of the
  // external work in the same pass (its sum in tile_sum_); the others once the bodies have moved
  // (positions_and_work).
  double *u = u_.data(), *du = du_.data(), *dth = dtheta_.data();
  const double *v = v_.data(), *om = omega_.data();
  double* sums = tile_sum_.data();
  dt_increment_s_ = dt;
  increments_everywhere_ = false;
  velocity_moved_ = false;
  on_node_ranges([&](std::size_t i0, std::size_t i1) {
    for (std::size_t b = i0; b < i1; b += kNodeTile) {
      const std::size_t k0 = 3 * b, k1 = 3 * std::min(i1, b + kNodeTile);
      double& sum = sums[b / kNodeTile];
      if (rigid_tile_[b / kNodeTile])
        advance_displacement(u + k0, du + k0, dth + k0, v + k0, om + k0, dt, k1 - k0);
      else
        sum = displacement_tile(b, k0, k1, dt);
    }
  });
}

double Solver::displacement_tile(std::size_t b, std::size_t k0, std::size_t k1, double dt) {
  double *u = u_.data(), *du = du_.data(), *dth = dtheta_.data(), *x = x_.data();
  const double *v = v_.data(), *om = omega_.data(), *x0 = model_.nodes.x0.data(),
               *fe = f_ext_.data();
  const bool turn = turning(b);
  const bool store = increment_tile_.empty() || increment_tile_[b / kNodeTile];
  // the eight instances: external loads, a tile that turns, increments stored
  const auto pass = [&]<bool kExt, bool kTurn, bool kStore>() {
    return displacement_pass<kExt, kTurn, kStore>(u, du, dth, v, om, x0, fe, x, dt, k0, k1);
  };
  const auto by_store = [&]<bool kExt, bool kTurn>() {
    return store ? pass.template operator()<kExt, kTurn, true>()
                 : pass.template operator()<kExt, kTurn, false>();
  };
  const auto by_turn = [&]<bool kExt>() {
    return turn ? by_store.template operator()<kExt, true>()
                : by_store.template operator()<kExt, false>();
  };
  return external_loads_ ? by_turn.template operator()<true>()
                         : by_turn.template operator()<false>();
}

double Solver::external_increment_work(std::size_t i0, std::size_t i1) const {
  const double* __restrict f = f_ext_.data();
  double s = 0.0;
  if (stored_increment(i0)) {
    const double* __restrict du = du_.data();
    for (std::size_t k = 3 * i0; k < 3 * i1; ++k) s += f[k] * du[k];
    return s;
  }
  // f (dt v): du_at's product, rounded alike
  const double dt = dt_increment_s_;
  const double* __restrict v = velocity_moved_ ? v_prev_.data() : v_.data();
  for (std::size_t k = 3 * i0; k < 3 * i1; ++k) s += f[k] * (dt * v[k]);
  return s;
}

Solver::StepWork Solver::positions_and_work() {
  StepWork w;
  const double *x0 = model_.nodes.x0.data(), *u = u_.data(), *du = du_.data(), *fe = f_ext_.data();
  // per tile of nodes, the tiles' sums in tile order (velocity_pass); advance_positions did
  // the tiles without rigid nodes
  double* x = x_.data();
  double* sums = tile_sum_.data();
  if (any_rigid_tile_)
    on_node_ranges([&](std::size_t i0, std::size_t i1) {
      for (std::size_t b = i0; b < i1; b += kNodeTile) {
        if (!rigid_tile_[b / kNodeTile]) continue;
        const std::size_t k0 = 3 * b, k1 = 3 * std::min(i1, b + kNodeTile);
        if (external_loads_)
          positions_pass<true>(x0, u, du, fe, x, k0, k1, sums[b / kNodeTile]);
        else
          positions_pass<false>(x0, u, du, fe, x, k0, k1, sums[b / kNodeTile]);
      }
    });
  w.external = 0.0;
  for (std::size_t t = 0; t < tiles(); ++t) w.external += sums[t];
  w.contact = increment_dot(contact_nodes_.nodes(), f_cont_.data());
  // The coupling loads live on few nodes: their work in index order (the sums over all dofs,
  // which add exact zeros elsewhere), then cleared.
  coupled_.sort();
  double coup = 0.0, mom = 0.0;
  double* __restrict fk = f_coup_.data();
  double* __restrict mk = m_coup_.data();
  for (const auto node : coupled_.nodes()) {
    const auto i = static_cast<std::size_t>(node);
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
      coup += fk[k] * du_at(k);
      mom += mk[k] * dtheta_at(k);
      fk[k] = 0.0;
      mk[k] = 0.0;
    }
  }
  w.coupling = coup;
  w.coupling_moment = mom;
  coupled_.clear();
  return w;
}

}  // namespace crashlink::integration
