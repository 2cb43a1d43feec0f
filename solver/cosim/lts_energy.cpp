// LtsEnergy: one domain's share of the `lts` scheme's conserved energy (lts_energy.h).
#include "solver/cosim/lts_energy.h"

#include <span>
#include <string>
#include <utility>

namespace crashlink::cosim {

void LtsEnergy::reset(std::vector<std::uint8_t> owned, std::vector<std::uint8_t> fixed,
                      std::vector<double> mass_kg, std::vector<double> inertia_kgm2,
                      double coarse_step_s) {
  owned_ = std::move(owned);
  fixed_ = std::move(fixed);
  mass_ = std::move(mass_kg);
  inertia_ = std::move(inertia_kgm2);
  rotating_.clear();
  for (std::size_t i = 0; i < mass_.size(); ++i)
    if (owned_[i] && i < inertia_.size() && inertia_[i] > 0.0)
      rotating_.push_back(static_cast<std::int32_t>(i));
  const std::size_t n3 = 3 * mass_.size();
  u1_.assign(n3, 0.0);
  u2_.assign(n3, 0.0);
  theta_.assign(rotating_.empty() ? 0 : n3, 0.0);
  t1_.assign(theta_.size(), 0.0);
  t2_.assign(theta_.size(), 0.0);
  h2_ = coarse_step_s * coarse_step_s;
  samples_ = 0;
  value_J_ = 0.0;
}

void LtsEnergy::add_rotation(const double* omega_mid, double dt_s) {
  for (const auto node : rotating_)
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(node) + d;
      theta_[k] += dt_s * omega_mid[k];
    }
}

void LtsEnergy::sample(const double* u) {
  // e_i = m_i / (2 H^2) [ |u^{k} - u^{k-1}|^2 - u^{k} . (u^{k} - 2 u^{k-1} + u^{k-2}) ]
  // (Diaz & Grote 2009, Theorem 3.1, with K_H u^{k-1} written by the scheme's own recurrence).
  ++samples_;
  double sum = 0.0;
  const std::size_t n = mass_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!owned_[i]) continue;
    double s = 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * i + d;
      if (!fixed_.empty() && (fixed_[i] & (1u << d))) continue;
      const double du = u[k] - u1_[k];
      s += du * du - u[k] * (du - (u1_[k] - u2_[k]));
    }
    sum += mass_[i] * s;
  }
  for (const auto node : rotating_) {  // the same with I_i and theta_i
    const auto i = static_cast<std::size_t>(node);
    double s = 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      const std::size_t k = 3 * i + d;
      if (!fixed_.empty() && (fixed_[i] & (1u << (3 + d)))) continue;
      const double dt = theta_[k] - t1_[k];
      s += dt * dt - theta_[k] * (dt - (t1_[k] - t2_[k]));
    }
    sum += inertia_[i] * s;
  }
  t2_.swap(t1_);
  t1_ = theta_;
  value_J_ = sum / (2.0 * h2_);
  u2_.swap(u1_);
  u1_.assign(u, u + 3 * n);
}

void LtsEnergy::save(core::StateWriter& w, const std::string& prefix) const {
  w.put(prefix + "u1", std::span<const double>(u1_));
  w.put(prefix + "u2", std::span<const double>(u2_));
  w.put(prefix + "theta", std::span<const double>(theta_));
  w.put(prefix + "t1", std::span<const double>(t1_));
  w.put(prefix + "t2", std::span<const double>(t2_));
  w.put_int(prefix + "samples", samples_);
  w.put_double(prefix + "value_J", value_J_);
}

void LtsEnergy::restore(const core::StateReader& r, const std::string& prefix) {
  r.get_exact(prefix + "u1", u1_);
  r.get_exact(prefix + "u2", u2_);
  r.get_exact(prefix + "theta", theta_);
  r.get_exact(prefix + "t1", t1_);
  r.get_exact(prefix + "t2", t2_);
  samples_ = r.get_int(prefix + "samples");
  value_J_ = r.get_double(prefix + "value_J");
}

}  // namespace crashlink::cosim
