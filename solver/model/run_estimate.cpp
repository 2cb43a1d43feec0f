#include "solver/model/run_estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace crashlink::model {

namespace {

/// Shortest edge of element e of part p [m] (hex: its 12 edges; shell: its 4).
double shortest_edge_m(const Model& m, const Part& p, std::size_t e) {
  static constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                           {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static constexpr int kQuadEdges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const bool hex = p.kind == ElementKind::Hex8;
  const auto k = static_cast<std::size_t>(nodes_per_element(p.kind));
  const std::int32_t* c = p.connectivity.data() + k * e;
  double best = std::numeric_limits<double>::infinity();
  const int count = hex ? 12 : 4;
  for (int j = 0; j < count; ++j) {
    const auto a = static_cast<std::size_t>(c[hex ? kHexEdges[j][0] : kQuadEdges[j][0]]);
    const auto b = static_cast<std::size_t>(c[hex ? kHexEdges[j][1] : kQuadEdges[j][1]]);
    if (a == b) continue;  // a degenerate quad (triangle)
    double s2 = 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      const double dx = m.nodes.x0[3 * a + d] - m.nodes.x0[3 * b + d];
      s2 += dx * dx;
    }
    if (s2 > 0.0) best = std::min(best, std::sqrt(s2));
  }
  return best;
}

bool deformable(const Model& m, const Part& p) {
  return m.materials[static_cast<std::size_t>(p.material)].kind != materials::MaterialKind::Rigid;
}

}  // namespace

double estimated_stable_step_s(const Model& m) {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& p : m.parts) {
    if (!deformable(m, p)) continue;
    const auto& mat = m.materials[static_cast<std::size_t>(p.material)];
    const double c = p.kind == ElementKind::Hex8 ? mat.dilatational_wave_speed_m_s()
                                                 : mat.plate_wave_speed_m_s();
    // The kernels' length on a cube or a square: the one-point hex's V sqrt(3 / (2 B:B)) = h /
    // sqrt(3), the shell's A / (its longest diagonal) = h / sqrt(2).
    const double shape = p.kind == ElementKind::Hex8 ? 1.0 / std::sqrt(3.0) : 1.0 / std::sqrt(2.0);
    // mass scaling: the element's wave speed c / sqrt(s)
    for (std::size_t e = 0; e < p.element_count(); ++e)
      dt = std::min(dt, shape * shortest_edge_m(m, p, e) / c * std::sqrt(p.density_scale_of(e)));
  }
  dt *= m.controls.dt_scale;
  if (m.controls.dt_max_s > 0.0) dt = std::min(dt, m.controls.dt_max_s);
  return dt;
}

RunEstimate estimate_run(const Model& m, double dt_s) {
  RunEstimate r;
  r.dt_s = dt_s;
  const auto& c = m.controls;
  r.cycles = std::isfinite(dt_s) && dt_s > 0.0 ? std::ceil(c.end_time_s / dt_s) : 1.0;
  double elements = 0.0, values_per_element = 0.0;
  for (const auto& p : m.parts) {
    values_per_element += 8.0 * static_cast<double>(p.element_count());
    if (deformable(m, p)) elements += static_cast<double>(p.element_count());
  }
  r.cpu_s = r.cycles * elements * kElementCycleCost_s;
  const double rows = c.history_interval_s > 0.0
                          ? std::min(r.cycles, c.end_time_s / c.history_interval_s) + 1.0
                          : r.cycles + 1.0;
  const double row_values = 12.0 + 9.0 * static_cast<double>(m.probes.size()) +
                            3.0 * static_cast<double>(m.contacts.size());
  const double states =
      c.field_interval_s > 0.0 ? std::min(r.cycles, c.end_time_s / c.field_interval_s) + 1.0 : 2.0;
  const double state_values = 6.0 * static_cast<double>(m.nodes.count()) + values_per_element;
  r.output_bytes = 8.0 * (rows * row_values + states * state_values);
  return r;
}

std::string byte_size(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

std::string duration(double seconds) {
  if (seconds >= 86400.0) return fmt::format("{:.3g} days", seconds / 86400.0);
  if (seconds >= 3600.0) return fmt::format("{:.3g} h", seconds / 3600.0);
  if (seconds >= 60.0) return fmt::format("{:.3g} min", seconds / 60.0);
  return fmt::format("{:.3g} s", seconds);
}

std::string describe(const RunEstimate& e) {
  return fmt::format(
      "~{:.3g} cycles at dt ~{:.3g} s, ~{} of CPU (mono, {:.0f} ns per element-cycle), ~{} of "
      "output",
      e.cycles, e.dt_s, duration(e.cpu_s), kElementCycleCost_s * 1e9, byte_size(e.output_bytes));
}

}  // namespace crashlink::model
