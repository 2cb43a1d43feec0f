#include "solver/materials/material.h"

#include <cmath>

#include "core/errors.h"

namespace crashlink::materials {

double HardeningCurve::yield(double ep) const {
  const std::size_t n = eps_p.size();
  if (n == 1) return sigma_y_Pa[0];
  std::size_t i = 1;
  while (i + 1 < n && ep > eps_p[i]) ++i;
  const double s = (sigma_y_Pa[i] - sigma_y_Pa[i - 1]) / (eps_p[i] - eps_p[i - 1]);
  return sigma_y_Pa[i - 1] + s * (ep - eps_p[i - 1]);
}

double HardeningCurve::slope(double ep) const {
  const std::size_t n = eps_p.size();
  if (n == 1) return 0.0;
  std::size_t i = 1;
  while (i + 1 < n && ep >= eps_p[i]) ++i;
  return (sigma_y_Pa[i] - sigma_y_Pa[i - 1]) / (eps_p[i] - eps_p[i - 1]);
}

double Material::dilatational_wave_speed_m_s() const {
  return std::sqrt((lame_lambda_Pa() + 2.0 * shear_modulus_Pa()) / density_kg_m3);
}

double Material::plate_wave_speed_m_s() const {
  return std::sqrt(youngs_modulus_Pa / (density_kg_m3 * (1.0 - poisson_ratio * poisson_ratio)));
}

void validate(const Material& m) {
  auto fail = [&](const std::string& what) {
    throw ModelError(fmt::format("material '{}': {}", m.name, what));
  };
  if (!(m.density_kg_m3 > 0.0))
    fail(fmt::format("density {} kg/m^3 must be > 0 (steel: 7850)", m.density_kg_m3));
  if (m.kind == MaterialKind::Rigid) return;
  if (!(m.youngs_modulus_Pa > 0.0))
    fail(fmt::format("Young's modulus {} Pa must be > 0 (steel: 2.1e11)", m.youngs_modulus_Pa));
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    fail(fmt::format("Poisson ratio {} must be in (-1, 0.5) (steel: 0.3)", m.poisson_ratio));
  if (m.kind != MaterialKind::J2Plastic) return;
  if (m.rate_c_per_s < 0.0 || (m.rate_c_per_s > 0.0 && !(m.rate_p > 0.0)))
    fail(
        fmt::format("Cowper-Symonds C = {} 1/s, P = {}: C must be >= 0 (0: no rate effect) and "
                    "P > 0 with it (mild steel: C 40.4, P 5)",
                    m.rate_c_per_s, m.rate_p));
  const auto& h = m.hardening;
  if (h.eps_p.empty() || h.eps_p.size() != h.sigma_y_Pa.size())
    fail(
        fmt::format("hardening curve needs as many eps_p ({}) as sigma_y ({}) values, at least one",
                    h.eps_p.size(), h.sigma_y_Pa.size()));
  if (h.eps_p[0] != 0.0)
    fail(fmt::format("hardening curve must start at eps_p = 0, not {}", h.eps_p[0]));
  for (std::size_t i = 0; i < h.eps_p.size(); ++i) {
    if (!(h.sigma_y_Pa[i] > 0.0))
      fail(fmt::format("yield stress {} Pa at point {} must be > 0", h.sigma_y_Pa[i], i));
    if (i > 0 && !(h.eps_p[i] > h.eps_p[i - 1]))
      fail(fmt::format("hardening curve eps_p must increase strictly: point {} has {} after {}", i,
                       h.eps_p[i], h.eps_p[i - 1]));
  }
}

}  // namespace crashlink::materials
