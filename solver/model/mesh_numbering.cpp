// Id numbering shared by the mesh generators (mesh_generators.h).
#include <algorithm>

#include "solver/model/mesh_generators.h"

namespace crashlink::model {

std::int64_t next_node_id(const Model& m) {
  std::int64_t last = 0;
  for (auto id : m.nodes.id) last = std::max(last, id);
  return last + 1;
}

std::int64_t next_element_id(const Model& m) {
  std::int64_t last = 0;
  for (const auto& p : m.parts)
    for (auto id : p.element_id) last = std::max(last, id);
  return last + 1;
}

int append_part(Model& m, Part part) {
  const std::int64_t first = next_element_id(m);
  const std::size_t ne = part.element_count();
  part.element_id.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) part.element_id[e] = first + static_cast<std::int64_t>(e);
  m.parts.push_back(std::move(part));
  if (!m.fixed.empty()) m.fixed.resize(m.nodes.count(), 0);
  return static_cast<int>(m.parts.size()) - 1;
}

}  // namespace crashlink::model
