// LtsEnergy: one domain's share of the `lts` scheme's conserved energy (lts_energy.h).
#include "solver/cosim/lts_energy.h"

#include <algorithm>
#include <span>
#include <string>
#include <utility>

namespace crashlink::cosim {

void LtsEnergy::reset(std::vector<std::uint8_t> owned, std::vector<std::uint8_t> fixed,
                      std::vector<double> mass_kg, std::vector<double> inertia_kgm2,
                      double coarse_step_s) {
  const std::size_t n = mass_kg.size();
  const std::size_t n3 = 3 * n;
  // Per dof the weight of its term: m_i (I_i) for a free dof of an owned node, else 0; the sums
  // then run over contiguous arrays without a branch.
  weight_.assign(n3, 0.0);
  bool any_rotating = false;
  std::vector<double> weight_rot(n3, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!owned[i]) continue;
    const bool rot = i < inertia_kgm2.size() && inertia_kgm2[i] > 0.0;
    any_rotating = any_rotating || rot;
    for (std::size_t d = 0; d < 3; ++d) {
      const bool held = !fixed.empty() && (fixed[i] & (1u << d));
      const bool held_rot = !fixed.empty() && (fixed[i] & (1u << (3 + d)));
      weight_[3 * i + d] = held ? 0.0 : mass_kg[i];
      weight_rot[3 * i + d] = rot && !held_rot ? inertia_kgm2[i] : 0.0;
    }
  }
  weight_rot_ = !any_rotating ? std::vector<double>() : std::move(weight_rot);
  u1_.assign(n3, 0.0);
  u2_.assign(n3, 0.0);
  theta_.assign(!any_rotating ? 0 : n3, 0.0);
  t1_.assign(theta_.size(), 0.0);
  t2_.assign(theta_.size(), 0.0);
  h2_ = coarse_step_s * coarse_step_s;
  samples_ = 0;
  last_k_ = -1;
  ready_ = false;
  value_J_ = 0.0;
}

void LtsEnergy::add_rotation(const double* omega_mid, double dt_s) {
  // every dof, one vectorised pass; the sums weigh the non-rotating and held ones 0 (their omega
  // is finite: the solver's kinetic sum multiplies it by I = 0 as well)
  if (theta_.empty()) return;
  const double* __restrict om = omega_mid;
  double* __restrict th = theta_.data();
  const std::size_t n3 = theta_.size();
  for (std::size_t k = 0; k < n3; ++k) th[k] += dt_s * om[k];
}

namespace {

/// sum_k w_k [ (x_k - a_k)^2 - x_k ((x_k - a_k) - (a_k - b_k)) ] over [0, n), in four partial
/// sums (k mod 4; independent lanes the compiler can put in one vector), added pairwise.
double weighted_terms(const double* __restrict w, const double* __restrict x,
                      const double* __restrict a, const double* __restrict b, std::size_t n) {
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4)
    for (std::size_t j = 0; j < 4; ++j) {
      const double d = x[k + j] - a[k + j];
      s[j] += w[k + j] * (d * d - x[k + j] * (d - (a[k + j] - b[k + j])));
    }
  for (; k < n; ++k) {
    const double d = x[k] - a[k];
    s[k % 4] += w[k] * (d * d - x[k] * (d - (a[k] - b[k])));
  }
  return (s[0] + s[1]) + (s[2] + s[3]);
}

}  // namespace

void LtsEnergy::sample(const double* u, std::int64_t k, bool evaluate) {
  // e_i = m_i / (2 H^2) [ |u^{k} - u^{k-1}|^2 - u^{k} . (u^{k} - 2 u^{k-1} + u^{k-2}) ]
  // (Diaz & Grote 2009, Theorem 3.1, with K_H u^{k-1} written by the scheme's own recurrence);
  // the same with I_i and theta_i for the rotating nodes.
  samples_ = last_k_ == kAnyNext || k == last_k_ + 1 ? samples_ + 1 : 1;
  last_k_ = k;
  const std::size_t n3 = u1_.size();
  ready_ = evaluate && samples_ >= 3;
  if (ready_) {
    double sum = weighted_terms(weight_.data(), u, u1_.data(), u2_.data(), n3);
    if (!theta_.empty())
      sum += weighted_terms(weight_rot_.data(), theta_.data(), t1_.data(), t2_.data(), n3);
    value_J_ = sum / (2.0 * h2_);
  }
  u2_.swap(u1_);
  std::copy(u, u + n3, u1_.begin());
  t2_.swap(t1_);
  std::copy(theta_.begin(), theta_.end(), t1_.begin());
}

void LtsEnergy::save(core::StateWriter& w, const std::string& prefix) const {
  w.put(prefix + "u1", std::span<const double>(u1_));
  w.put(prefix + "u2", std::span<const double>(u2_));
  w.put(prefix + "theta", std::span<const double>(theta_));
  w.put(prefix + "t1", std::span<const double>(t1_));
  w.put(prefix + "t2", std::span<const double>(t2_));
  w.put_int(prefix + "samples", samples_);
  w.put_int(prefix + "last_k", last_k_);
  w.put_int(prefix + "ready", ready_ ? 1 : 0);
  w.put_double(prefix + "value_J", value_J_);
}

void LtsEnergy::restore(const core::StateReader& r, const std::string& prefix) {
  r.get_exact(prefix + "u1", u1_);
  r.get_exact(prefix + "u2", u2_);
  r.get_exact(prefix + "theta", theta_);
  r.get_exact(prefix + "t1", t1_);
  r.get_exact(prefix + "t2", t2_);
  samples_ = r.get_int(prefix + "samples");
  // (checkpoints before 2026-11-28 sampled every instant: the next one follows)
  last_k_ = r.has(prefix + "last_k") ? r.get_int(prefix + "last_k") : kAnyNext;
  ready_ = r.has(prefix + "ready") ? r.get_int(prefix + "ready") != 0 : samples_ >= 3;
  value_J_ = r.get_double(prefix + "value_J");
}

}  // namespace crashlink::cosim
