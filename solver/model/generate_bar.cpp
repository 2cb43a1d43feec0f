// Bar generator (mesh_generators.h): a row of Hex8 elements along a coordinate axis.
#include "core/errors.h"
#include "solver/model/mesh_generators.h"

namespace crashlink::model {

int generate_bar(Model& m, Part part, const BarMesh& bar) {
  if (bar.axis < 0 || bar.axis > 2)
    throw ModelError(
        fmt::format("bar '{}': axis {} must be 0, 1 or 2 (x, y, z)", part.name, bar.axis));
  const std::size_t first = m.nodes.count();
  // Built along +x with the cross-section centred on the axis, then the coordinates are permuted
  // cyclically (x -> axis): a cyclic permutation keeps the orientation, so Jacobians stay > 0.
  const BoxMesh local{{0.0, -0.5 * bar.cross_section_m[0], -0.5 * bar.cross_section_m[1]},
                      {bar.length_m, bar.cross_section_m[0], bar.cross_section_m[1]},
                      {bar.elements, bar.cross_divisions[0], bar.cross_divisions[1]}};
  const int index = generate_box(m, std::move(part), local);
  for (std::size_t i = first; i < m.nodes.count(); ++i) {
    double* x = &m.nodes.x0[3 * i];
    const Vec3 l{x[0], x[1], x[2]};
    for (int c = 0; c < 3; ++c) x[(bar.axis + c) % 3] = l[static_cast<std::size_t>(c)];
    for (int c = 0; c < 3; ++c) x[c] += bar.origin_m[static_cast<std::size_t>(c)];
  }
  return index;
}

}  // namespace crashlink::model
