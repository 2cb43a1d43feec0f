#include "studies/contact_drop.h"

#include <cmath>

#include "solver/model/mesh_generators.h"
#include "solver/model/node_merging.h"

namespace crashlink::studies {

model::Model contact_drop_model(double r, double penalty_scale) {
  model::Model m;
  m.name = "contact_drop";
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
  const double dx = 0.01;  // m
  const double a = std::max(1.0, r) * dx;
  const double L = 8 * a;
  // Two element layers, two parts: the top one is the contact's master (what `layer` moves into
  // the fine domain: a master part moves whole), the bottom one stays coarse.
  model::Part slab;
  slab.name = "coarse";
  slab.material = 0;
  model::generate_box(m, slab, {{0, 0, -2 * a}, {L, L, a}, {8, 8, 1}});
  const std::size_t top_first = m.nodes.count();
  model::Part top = slab;
  top.name = "coarse_top";
  model::generate_box(m, top, {{0, 0, -a}, {L, L, a}, {8, 8, 1}});
  model::merge_coincident_nodes(m, top_first, 1e-6);
  const std::size_t first = m.nodes.count();
  model::Part block;
  block.name = "fine";
  block.material = 0;
  const double b = 4 * dx;
  model::generate_box(m, block, {{0.5 * (L - b), 0.5 * (L - b), 1e-3}, {b, b, b}, {4, 4, 4}});
  const std::size_t n = m.nodes.count();
  m.fixed.assign(n, 0);
  for (std::size_t i = 0; i < first; ++i)
    if (m.nodes.x0[3 * i + 2] < -2 * a + 1e-9) m.fixed[i] = 7;
  model::Contact c;
  c.name = "block_on_slab";
  for (std::size_t i = first; i < n; ++i) {
    c.slave_nodes.push_back(static_cast<std::int32_t>(i));
    m.initial_velocities.push_back({{static_cast<std::int32_t>(i)}, {0.0, 0.0, -2.0}});
  }
  c.master_parts = {1};
  c.penalty_scale = penalty_scale;
  m.contacts.push_back(c);
  m.controls.end_time_s = 100.0;
  m.controls.bulk_viscosity = true;
  m.domains = {{"coarse", {0, 1}}, {"fine", {2}}};
  return m;
}

FreeVibrationResult run_layer_contact_drop(double r, double penalty_scale,
                                           std::int64_t fine_steps) {
  return run_layer_energy(contact_drop_model(r, penalty_scale), r, fine_steps);
}

FreeVibrationResult run_paper_contact_drop(double r, double penalty_scale, std::int64_t fine_steps,
                                           bool drift) {
  return run_paper_energy(contact_drop_model(r, penalty_scale), r, fine_steps, drift);
}

}  // namespace crashlink::studies
