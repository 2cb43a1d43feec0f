#include "solver/integration/mass_scaling.h"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"
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

namespace {

/// The part's lumped mass [kg] (the kernels' functions, with its density factors or without).
double part_mass_kg(const model::Model& m, const model::Part& p) {
  const auto& mat = m.materials[static_cast<std::size_t>(p.material)];
  std::vector<double> mass(m.nodes.count(), 0.0), inertia(m.nodes.count(), 0.0);
  if (p.kind == model::ElementKind::Hex8)
    elements::hex8_lumped_mass(p, mat, m.nodes.x0.data(), mass.data());
  else
    elements::shell_lumped_mass(p, mat, m.nodes.x0.data(), mass.data(), inertia.data());
  double sum = 0.0;
  for (double x : mass) sum += x;
  return sum;
}

}  // namespace

MassScalingReport describe_mass_scaling(const model::Model& m) {
  MassScalingReport r;
  r.target_dt_s = m.controls.mass_scaling_dt_s;
  for (const auto& p : m.parts) {
    if (is_rigid(m, p)) continue;
    r.deformable_elements += p.element_count();
    if (p.element_density_scale.empty()) {
      r.mass_kg += part_mass_kg(m, p);
      continue;
    }
    model::Part unscaled = p;
    unscaled.element_density_scale.clear();
    const double before = part_mass_kg(m, unscaled);
    r.mass_kg += before;
    r.added_mass_kg += part_mass_kg(m, p) - before;
    for (std::size_t e = 0; e < p.element_count(); ++e) {
      const double f = p.element_density_scale[e];
      if (f > 1.0) ++r.scaled_elements;
      if (f > r.largest_factor) {
        r.largest_factor = f;
        r.largest_element = fmt::format("element {} of part '{}'", p.element_id[e], p.name);
      }
    }
  }
  return r;
}

MassScalingReport apply_mass_scaling(model::Model& m) {
  const double target = m.controls.mass_scaling_dt_s;
  for (auto& part : m.parts) part.element_density_scale.clear();
  if (!(target > 0.0)) return describe_mass_scaling(m);
  if (target >= m.controls.end_time_s)
    throw ModelError(fmt::format(
        "mass scaling to a stable step of {} s, at or above the end time {} s: every element "
        "would weigh (step / its step)^2 times more; fix: give the step in seconds (crash "
        "meshes step at 1e-7 to 1e-5 s)",
        target, m.controls.end_time_s));
  std::vector<std::vector<double>> steps(m.parts.size());
  {
    model::Model mono = m;  // the steps of the whole model, as one domain
    mono.domains.clear();
    Solver s(mono, m.name);
    s.record_element_steps(true);
    s.initialize();
    for (std::size_t p = 0; p < m.parts.size(); ++p) steps[p] = s.parts()[p].element_dt_s;
  }
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    auto& part = m.parts[p];
    if (is_rigid(m, part)) continue;
    const auto& dt = steps[p];
    if (dt.size() != part.element_count()) continue;  // (a part the solver did not step)
    std::vector<double> scale(part.element_count(), 1.0);
    bool any = false;
    for (std::size_t e = 0; e < dt.size(); ++e) {
      if (!(dt[e] > 0.0) || !std::isfinite(dt[e]))
        throw ModelError(fmt::format(
            "mass scaling: element {} of part '{}' has no finite positive stable step ({} s); "
            "fix: check its corners and thickness",
            part.element_id[e], part.name, dt[e]));
      if (!(dt[e] < target)) continue;
      // dt ~ sqrt(rho): the factor (dt_target / dt)^2
      const double ratio = target / dt[e];
      scale[e] = ratio * ratio;
      any = true;
    }
    if (any) part.element_density_scale = std::move(scale);
  }
  return describe_mass_scaling(m);
}

}  // namespace crashlink::integration
