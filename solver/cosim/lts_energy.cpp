// LtsEnergy: one domain's share of the `lts` scheme's conserved energy (lts_energy.h).
#include "solver/cosim/lts_energy.h"

#include <span>
#include <string>
#include <utility>

namespace crashlink::cosim {

void LtsEnergy::reset(std::vector<std::uint8_t> owned, std::vector<std::uint8_t> fixed,
                      std::vector<double> mass_kg, double coarse_step_s) {
  owned_ = std::move(owned);
  fixed_ = std::move(fixed);
  mass_ = std::move(mass_kg);
  u1_.assign(3 * mass_.size(), 0.0);
  u2_.assign(3 * mass_.size(), 0.0);
  h2_ = coarse_step_s * coarse_step_s;
  samples_ = 0;
  value_J_ = 0.0;
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
  value_J_ = sum / (2.0 * h2_);
  u2_.swap(u1_);
  u1_.assign(u, u + 3 * n);
}

void LtsEnergy::save(core::StateWriter& w, const std::string& prefix) const {
  w.put(prefix + "u1", std::span<const double>(u1_));
  w.put(prefix + "u2", std::span<const double>(u2_));
  w.put_int(prefix + "samples", samples_);
  w.put_double(prefix + "value_J", value_J_);
}

void LtsEnergy::restore(const core::StateReader& r, const std::string& prefix) {
  r.get_exact(prefix + "u1", u1_);
  r.get_exact(prefix + "u2", u2_);
  samples_ = r.get_int(prefix + "samples");
  value_J_ = r.get_double(prefix + "value_J");
}

}  // namespace crashlink::cosim
