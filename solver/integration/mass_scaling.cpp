#include "solver/integration/mass_scaling.h"

#include <fmt/format.h>

#include <cmath>

#include "solver/integration/solver.h"

namespace crashlink::integration {

std::string MassScalingReport::summary() const {
  return fmt::format(
      "mass scaling to a stable step of {:.4g} s (safety factor not included): {} of {} "
      "deformable elements scaled, {:.4g} kg added to the model's {:.4g} kg ({:.3g} %); the "
      "largest density factor {:.4g} at {}",
      target_dt_s, scaled_elements, deformable_elements, added_mass_kg, mass_kg,
      mass_kg > 0.0 ? 100.0 * added_mass_kg / mass_kg : 0.0, largest_factor,
      largest_element.empty() ? std::string("no element") : largest_element);
}

MassScalingReport apply_mass_scaling(model::Model& m) {
  MassScalingReport r;
  r.target_dt_s = m.controls.mass_scaling_dt_s;
  if (!(r.target_dt_s > 0.0)) return r;
  std::vector<std::vector<double>> steps(m.parts.size());
  {
    model::Model mono = m;  // the steps of the whole model, as one domain
    mono.domains.clear();
    Solver s(mono, m.name);
    s.record_element_steps(true);
    s.initialize();
    r.mass_kg = s.total_mass_kg();
    for (std::size_t p = 0; p < m.parts.size(); ++p) steps[p] = s.parts()[p].element_dt_s;
  }
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    auto& part = m.parts[p];
    if (m.materials[static_cast<std::size_t>(part.material)].kind == materials::MaterialKind::Rigid)
      continue;
    r.deformable_elements += part.element_count();
    const auto& dt = steps[p];
    if (dt.size() != part.element_count()) continue;  // (a part the solver did not step)
    std::vector<double> scale(part.element_count(), 1.0);
    bool any = false;
    for (std::size_t e = 0; e < dt.size(); ++e) {
      if (!(dt[e] < r.target_dt_s)) continue;
      // dt ~ sqrt(rho): (dt_target / dt)^2 on top of the factor the element already has
      const double ratio = r.target_dt_s / dt[e];
      scale[e] = part.density_scale_of(e) * ratio * ratio;
      if (!(scale[e] > part.density_scale_of(e))) continue;
      any = true;
      ++r.scaled_elements;
      if (scale[e] > r.largest_factor) {
        r.largest_factor = scale[e];
        r.largest_element = fmt::format("element {} of part '{}'", part.element_id[e], part.name);
      }
    }
    if (!any) continue;
    if (!part.element_density_scale.empty())
      for (std::size_t e = 0; e < dt.size(); ++e)
        scale[e] = std::max(scale[e], part.element_density_scale[e]);
    part.element_density_scale = std::move(scale);
  }
  if (r.scaled_elements > 0) {
    model::Model mono = m;
    mono.domains.clear();
    Solver s(mono, m.name);
    s.initialize();
    r.added_mass_kg = s.total_mass_kg() - r.mass_kg;
  }
  return r;
}

}  // namespace crashlink::integration
