// Plate generator (mesh_generators.h): a structured parallelogram of Shell4 elements.
#include <algorithm>
#include <cstdint>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/unit_noise.h"

namespace crashlink::model {

int generate_plate(Model& m, Part part, const PlateMesh& plate) {
  const int n1 = plate.divisions[0], n2 = plate.divisions[1];
  if (n1 < 1 || n2 < 1 || !(norm(cross(plate.edge1_m, plate.edge2_m)) > 0.0))
    throw ModelError(fmt::format(
        "plate '{}': divisions [{}, {}] must be >= 1 and the edges non-zero and not parallel",
        part.name, n1, n2));
  if (plate.distort < 0.0 || plate.distort > 0.4)
    throw ModelError(fmt::format("plate '{}': distort {} outside [0, 0.4] (quads would fold)",
                                 part.name, plate.distort));
  const std::int64_t id0 = next_node_id(m);
  const auto base = static_cast<std::int32_t>(m.nodes.count());
  const double l1 = norm(plate.edge1_m), l2 = norm(plate.edge2_m);
  const double h_min = std::min(l1 / n1, l2 / n2);
  const Vec3 t1 = (1.0 / l1) * plate.edge1_m, t2 = (1.0 / l2) * plate.edge2_m;
  // Node (i, j) at index base + i + (n1+1) j; x = origin + (i/n1) edge1 + (j/n2) edge2.
  std::int64_t id = id0;
  for (int j = 0; j <= n2; ++j)
    for (int i = 0; i <= n1; ++i) {
      Vec3 x = plate.origin_m + (static_cast<double>(i) / n1) * plate.edge1_m +
               (static_cast<double>(j) / n2) * plate.edge2_m;
      const bool interior = i > 0 && i < n1 && j > 0 && j < n2;
      if (interior && plate.distort > 0.0) {
        const auto key = static_cast<std::uint64_t>(i + (n1 + 1) * j);
        const double a = plate.distort * h_min;
        x = x + (a * unit_noise(2 * key)) * t1 + (a * unit_noise(2 * key + 1)) * t2;
      }
      m.nodes.id.push_back(id++);
      m.nodes.x0.insert(m.nodes.x0.end(), x.begin(), x.end());
    }
  auto node = [&](int i, int j) { return base + i + (n1 + 1) * j; };
  part.kind = ElementKind::Shell4;
  part.connectivity.clear();
  part.connectivity.reserve(4 * static_cast<std::size_t>(n1) * n2);
  for (int j = 0; j < n2; ++j)
    for (int i = 0; i < n1; ++i)
      for (int c : {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)})
        part.connectivity.push_back(c);
  return append_part(m, std::move(part));
}

}  // namespace crashlink::model
