// Plausibility checks on a read scenario (docs/scenario-format.md "Plausibility checks"): values
// that are valid one by one but implausible for their neighbours, most likely a unit mistake (a
// thickness in mm, a modulus in GPa, an end time in ms). Each refusal fails at the key's line with
// the values, the likely mistake and the fix; `controls.plausibility_checks: false` turns them off.
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "solver/io/scenario_sections.h"
#include "solver/model/run_estimate.h"

namespace crashlink::io::detail {

namespace {

constexpr const char* kOverride =
    "(if the value is meant, set controls.plausibility_checks: false)";

/// Wave speeds sqrt(E / rho) a crash material has [m/s]: soft foams ~100, steel 5200, beryllium
/// 12 900; outside, E or rho is almost surely in another unit (MPa, GPa; g/cm^3, t/mm^3).
constexpr double kMinWaveSpeed_m_s = 100.0;
constexpr double kMaxWaveSpeed_m_s = 20000.0;
/// Most cycles a scenario may plan (1e8 cycles of a 10^4-element model: 19 h of CPU).
constexpr double kMaxCycles = 1e8;
/// Most output a scenario may plan [bytes].
constexpr double kMaxOutputBytes = 100e9;
/// An end time from this on [s] is a slow event for a crash code (impacts last milliseconds); it
/// is refused when the run is also long or large (an end time in ms written as s).
constexpr double kLongEndTime_s = 1.0;
constexpr double kLongRunCpu_s = 3600.0;
constexpr double kLargeOutputBytes = 1e9;

/// Largest sqrt(area) of the shells of part p [m]: the in-plane element size (the two diagonals'
/// cross product for a quad, |d1 x d2| / 2 = area).
double largest_shell_size_m(const model::Model& m, const model::Part& p) {
  double best = 0.0;
  for (std::size_t e = 0; e < p.element_count(); ++e) {
    const std::int32_t* c = p.connectivity.data() + 4 * e;
    auto x = [&](int j) {
      const auto k = static_cast<std::size_t>(c[j]);
      return Vec3{m.nodes.x0[3 * k], m.nodes.x0[3 * k + 1], m.nodes.x0[3 * k + 2]};
    };
    const double area = 0.5 * norm(cross(x(2) - x(0), x(3) - x(1)));
    best = std::max(best, std::sqrt(area));
  }
  return best;
}

void check_thickness(const YamlNode& parts, const ScenarioBuild& b) {
  for (const auto& [name, p] : parts.entries()) {
    const auto t = p.optional("thickness");
    if (!t) continue;
    const int idx = b.model.part_index(name);
    if (idx < 0) continue;
    const auto& part = b.model.parts[static_cast<std::size_t>(idx)];
    if (part.kind != model::ElementKind::Shell4) continue;
    const double size = largest_shell_size_m(b.model, part);
    if (part.thickness_m > size)
      t->fail(fmt::format(
          "{} m is above the part's element size {:.3g} m (its largest shell, sqrt of the area): "
          "a shell that thick is a solid; did you mean mm? write {:g} m {}",
          part.thickness_m, size, part.thickness_m * 1e-3, kOverride));
  }
}

void check_wave_speeds(const YamlNode& materials, const ScenarioBuild& b) {
  for (const auto& [name, mat] : materials.entries()) {
    const auto& m = b.model.materials[static_cast<std::size_t>(b.material_index.at(name))];
    if (m.kind == materials::MaterialKind::Rigid) continue;
    const double E = m.youngs_modulus_Pa, rho = m.density_kg_m3;
    const double c = std::sqrt(E / rho);
    if (c >= kMinWaveSpeed_m_s && c <= kMaxWaveSpeed_m_s) continue;
    // The rewrites that bring sqrt(E / rho) into range, likeliest first.
    std::vector<std::string> fixes;
    auto plausible = [](double e, double r) {
      const double s = std::sqrt(e / r);
      return s >= kMinWaveSpeed_m_s && s <= kMaxWaveSpeed_m_s;
    };
    if (c < kMinWaveSpeed_m_s) {
      if (plausible(E * 1e9, rho))
        fixes.push_back(fmt::format("youngs_modulus in GPa? write {:g} Pa", E * 1e9));
      if (plausible(E * 1e6, rho))
        fixes.push_back(fmt::format("youngs_modulus in MPa? write {:g} Pa", E * 1e6));
      if (plausible(E, rho * 1e-3))
        fixes.push_back(fmt::format("density in g/m^3? write {:g} kg/m^3", rho * 1e-3));
    } else {
      if (plausible(E, rho * 1e3))
        fixes.push_back(fmt::format("density in g/cm^3? write {:g} kg/m^3", rho * 1e3));
      if (plausible(E, rho * 1e12))
        fixes.push_back(fmt::format("density in t/mm^3? write {:g} kg/m^3", rho * 1e12));
    }
    const auto at = mat.optional("youngs_modulus") ? *mat.optional("youngs_modulus") : mat;
    at.fail(fmt::format(
        "wave speed sqrt(E / rho) = sqrt({:g} Pa / {:g} kg/m^3) = {:.3g} m/s is outside the "
        "{:g}-{:g} m/s of crash materials (steel 5200 m/s: E 210e9 Pa, rho 7850 kg/m^3); did you "
        "mean {} {}",
        E, rho, c, kMinWaveSpeed_m_s, kMaxWaveSpeed_m_s,
        fixes.empty() ? std::string("SI units (Pa, kg/m^3)?")
                      : fmt::format("{}?", fmt::join(fixes, "; or ")),
        kOverride));
  }
}

void check_probes(const YamlNode& probes, const ScenarioBuild& b) {
  const auto& m = b.model;
  const std::size_t n = m.nodes.count();
  if (n == 0) return;
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi = -1.0 * lo;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], m.nodes.x0[3 * i + d]);
      hi[d] = std::max(hi[d], m.nodes.x0[3 * i + d]);
    }
  const double size = norm(hi - lo);  // the model's bounding-box diagonal [m]
  std::size_t k = 0;
  for (const auto& [name, pr] : probes.entries()) {
    const auto& probe = m.probes[k++];
    const auto near = pr.optional("node_near");
    if (!near) continue;
    const Vec3 x = near->vec3();
    const auto i = static_cast<std::size_t>(probe.index);
    const Vec3 y{m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]};
    const double d = norm(y - x);
    if (d > size)
      near->fail(fmt::format(
          "[{:g}, {:g}, {:g}] is {:.3g} m from the nearest node (id {}), farther than the model's "
          "size {:.3g} m (its bounding box from [{:g}, {:g}, {:g}] to [{:g}, {:g}, {:g}]); did "
          "you mean mm? write [{:g}, {:g}, {:g}] {}",
          x[0], x[1], x[2], d, m.nodes.id[i], size, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2],
          x[0] * 1e-3, x[1] * 1e-3, x[2] * 1e-3, kOverride));
  }
}

void check_run_size(const YamlNode& controls, const ScenarioBuild& b) {
  const double dt = model::estimated_stable_step_s(b.model);
  if (!std::isfinite(dt)) return;
  const auto e = model::estimate_run(b.model, dt);
  const double end = b.model.controls.end_time_s;
  const bool absurd = e.cycles > kMaxCycles || e.output_bytes > kMaxOutputBytes;
  const bool slow_event =
      end >= kLongEndTime_s && (e.cpu_s > kLongRunCpu_s || e.output_bytes > kLargeOutputBytes);
  if (!absurd && !slow_event) return;
  controls.required("end_time")
      .fail(fmt::format(
          "{:g} s is {}: {}; crash events last milliseconds: did you mean ms? write {:g} s {}", end,
          model::describe(e),
          absurd ? fmt::format("more than the {:.0e} cycles or {} a scenario may plan", kMaxCycles,
                               model::byte_size(kMaxOutputBytes))
                 : fmt::format("an end time of {:g} s or more with over {} of CPU or {} of output",
                               kLongEndTime_s, model::duration(kLongRunCpu_s),
                               model::byte_size(kLargeOutputBytes)),
          end * 1e-3, kOverride));
}

}  // namespace

void check_plausibility(const YamlNode& root, const ScenarioBuild& b) {
  check_thickness(root.required("parts"), b);
  check_wave_speeds(root.required("materials"), b);
  if (auto p = root.optional("probes")) check_probes(*p, b);
  check_run_size(root.required("controls"), b);
}

}  // namespace crashlink::io::detail
