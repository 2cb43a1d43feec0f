// Lumped translational mass and rotational inertia of the Belytschko-Tsay shell.
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/vec3.h"
#include "solver/elements/shell_bt.h"

namespace crashlink::elements {

void shell_lumped_mass(const model::Part& part, const materials::Material& mat, const double* x0,
                       double* mass, double* inertia) {
  const std::size_t ne = part.element_count();
  const double rho = mat.density_kg_m3;
  auto node = [&](std::int32_t n) {
    const std::size_t i = 3 * static_cast<std::size_t>(n);
    return Vec3{x0[i], x0[i + 1], x0[i + 2]};
  };
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t* c = &part.connectivity[4 * e];
    const Vec3 x1 = node(c[0]), x2 = node(c[1]), x3 = node(c[2]), x4 = node(c[3]);
    // A = |r31 x r42| / 2 ([LSTM] BT shell, the area of the one-point quadrature).
    const double A = 0.5 * norm(cross(x3 - x1, x4 - x2));
    if (!(A > 0.0) || !std::isfinite(A))
      throw NumericalError(fmt::format(
          "part '{}', shell element {}: reference area {} m^2 is not positive; check the "
          "connectivity (repeated nodes other than n3 == n4) and the coordinates",
          part.name, part.element_id[e], A));
    const bool triangle = c[3] == c[2];
    const int corners = triangle ? 3 : 4;
    const double h = part.thickness_of(e);
    const double m_node = rho * part.density_scale_of(e) * h * A / corners;  // mass scaling
    // Rotary inertia with area scaling: I = m_node max(h^2/12, A/8) (see shell_bt.h).
    const double I_node = m_node * std::max(h * h / 12.0, A / 8.0);
    for (int i = 0; i < corners; ++i) {
      mass[c[i]] += m_node;
      inertia[c[i]] += I_node;
    }
  }
}

}  // namespace crashlink::elements
