// Box generator (mesh_generators.h): a structured block of Hex8 elements.
#include "core/errors.h"
#include "solver/model/mesh_generators.h"

namespace crashlink::model {

int generate_box(Model& m, Part part, const BoxMesh& box) {
  const int nx = box.divisions[0], ny = box.divisions[1], nz = box.divisions[2];
  if (nx < 1 || ny < 1 || nz < 1 || !(box.size_m[0] > 0.0) || !(box.size_m[1] > 0.0) ||
      !(box.size_m[2] > 0.0))
    throw ModelError(
        fmt::format("box '{}': size [{}, {}, {}] m and divisions [{}, {}, {}] must all be > 0",
                    part.name, box.size_m[0], box.size_m[1], box.size_m[2], nx, ny, nz));
  const std::int64_t id0 = next_node_id(m);
  const auto base = static_cast<std::int32_t>(m.nodes.count());
  // Node (i, j, k) at index base + i + (nx+1) (j + (ny+1) k); x = origin + size * i / nx.
  auto coord = [](double origin, double size, int i, int n) {
    return i == n ? origin + size : origin + size * static_cast<double>(i) / static_cast<double>(n);
  };
  std::int64_t id = id0;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        m.nodes.id.push_back(id++);
        m.nodes.x0.push_back(coord(box.origin_m[0], box.size_m[0], i, nx));
        m.nodes.x0.push_back(coord(box.origin_m[1], box.size_m[1], j, ny));
        m.nodes.x0.push_back(coord(box.origin_m[2], box.size_m[2], k, nz));
      }
  auto node = [&](int i, int j, int k) { return base + i + (nx + 1) * (j + (ny + 1) * k); };
  part.kind = ElementKind::Hex8;
  part.connectivity.clear();
  part.connectivity.reserve(8 * static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int c : {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                      node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                      node(i, j + 1, k + 1)})
          part.connectivity.push_back(c);
  return append_part(m, std::move(part));
}

}  // namespace crashlink::model
