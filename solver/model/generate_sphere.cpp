// Sphere generator (mesh_generators.h): the cube-sphere surface of Shell4 elements.
#include <cmath>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"

namespace crashlink::model {

int generate_sphere(Model& m, Part part, const SphereMesh& sphere) {
  const int n = sphere.divisions;
  if (n < 1 || !(sphere.radius_m > 0.0))
    throw ModelError(fmt::format("sphere '{}': radius {} m and divisions {} must be > 0", part.name,
                                 sphere.radius_m, n));
  const std::int64_t id0 = next_node_id(m);
  const auto base = static_cast<std::int32_t>(m.nodes.count());
  // Cube lattice (i, j, k) in [0, n]^3; only its surface points become nodes, each once (edges
  // and corners are shared by the faces). Equiangular coordinate: c(i) = tan(pi/4 (2i/n - 1)).
  std::vector<double> c(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i)
    c[static_cast<std::size_t>(i)] = i == 0 ? -1.0
                                     : i == n
                                         ? 1.0
                                         : std::tan(0.25 * std::numbers::pi * (2.0 * i / n - 1.0));
  const std::size_t side = static_cast<std::size_t>(n) + 1;
  std::vector<std::int32_t> index(side * side * side, -1);
  auto at = [&](int i, int j, int k) -> std::int32_t& {
    return index[static_cast<std::size_t>(i) +
                 side * (static_cast<std::size_t>(j) + side * static_cast<std::size_t>(k))];
  };
  std::int64_t id = id0;
  std::int32_t next = base;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        if (i != 0 && i != n && j != 0 && j != n && k != 0 && k != n) continue;
        const Vec3 p{c[static_cast<std::size_t>(i)], c[static_cast<std::size_t>(j)],
                     c[static_cast<std::size_t>(k)]};
        const Vec3 x = sphere.centre_m + (sphere.radius_m / norm(p)) * p;
        at(i, j, k) = next++;
        m.nodes.id.push_back(id++);
        m.nodes.x0.insert(m.nodes.x0.end(), x.begin(), x.end());
      }
  part.kind = ElementKind::Shell4;
  part.connectivity.clear();
  part.connectivity.reserve(24 * static_cast<std::size_t>(n) * n);
  // Face normal to axis d at lattice coordinate s in {0, n}; in-face axes a = d+1, b = d+2
  // (cyclic), so the quad (p,q) (p+1,q) (p+1,q+1) (p,q+1) has normal e_a x e_b = +e_d: outward
  // on the s = n face; reversed on the s = 0 face.
  for (int d = 0; d < 3; ++d)
    for (int s : {0, n})
      for (int q = 0; q < n; ++q)
        for (int p = 0; p < n; ++p) {
          auto lattice = [&](int pa, int qb) -> std::int32_t {
            int ijk[3];
            ijk[d] = s;
            ijk[(d + 1) % 3] = pa;
            ijk[(d + 2) % 3] = qb;
            return at(ijk[0], ijk[1], ijk[2]);
          };
          if (s == n) {
            for (auto v :
                 {lattice(p, q), lattice(p + 1, q), lattice(p + 1, q + 1), lattice(p, q + 1)})
              part.connectivity.push_back(v);
          } else {
            for (auto v :
                 {lattice(p, q), lattice(p, q + 1), lattice(p + 1, q + 1), lattice(p + 1, q)})
              part.connectivity.push_back(v);
          }
        }
  return append_part(m, std::move(part));
}

}  // namespace crashlink::model
