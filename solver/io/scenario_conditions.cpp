// Boundary conditions, prescribed velocities, loads and initial velocities
// (docs/scenario-format.md).
#include "solver/core/errors.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io::detail {

namespace {

/// A list of entries; a single entry may be written as a mapping without the list.
std::vector<YamlNode> entries_of(const YamlNode& section) {
  if (section.is_map()) return {section};
  return section.items("entries ('- nodes: ...' lines)");
}

}  // namespace

int read_dof(const YamlNode& dof, bool rotations) {
  const std::string s =
      rotations ? dof.choice({"x", "y", "z", "rx", "ry", "rz"}) : dof.choice({"x", "y", "z"});
  static const char* const names[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int i = 0; i < 6; ++i)
    if (s == names[i]) return i;
  return 0;  // unreachable: choice() accepted s
}

model::Curve read_value_or_curve(const YamlNode& entry, const std::string& constant_key) {
  const auto constant = entry.optional(constant_key);
  const auto curve = entry.optional("curve");
  if (constant && curve)
    curve->fail("give either '" + constant_key + "' (a constant) or 'curve', not both");
  if (constant) return model::Curve::constant(constant->number());
  if (!curve) entry.fail("needs '" + constant_key + ": number' or 'curve: {t: [s...], v: [...]}'");
  curve->expect_keys({"t", "v"});
  const auto t_node = curve->required("t", "times in s, increasing");
  const auto v_node = curve->required("v", "one value per time");
  model::Curve c;
  c.t_s = t_node.numbers(1);
  c.value = v_node.numbers(1);
  if (c.t_s.size() != c.value.size())
    v_node.fail(fmt::format("{} values for {} times; give one value per time", c.value.size(),
                            c.t_s.size()));
  for (std::size_t i = 1; i < c.t_s.size(); ++i)
    if (!(c.t_s[i] > c.t_s[i - 1]))
      t_node.fail(fmt::format("times must increase strictly: t[{}] = {} after {}", i, c.t_s[i],
                              c.t_s[i - 1]));
  return c;
}

void read_boundary(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"nodes", "fix"});
    const auto nodes = read_node_reference(e.required("nodes", "a node set name"), b);
    const auto fix = e.required("fix", "[x, y, z, rx, ry, rz] or all");
    std::uint8_t mask = 0;
    if (fix.is_scalar() && fix.text() == "all") {
      mask = model::kUx | model::kUy | model::kUz | model::kRx | model::kRy | model::kRz;
    } else {
      for (const auto& d : fix.items("degrees of freedom [x, y, z, rx, ry, rz] (or 'all')"))
        mask = static_cast<std::uint8_t>(mask | (1u << read_dof(d, true)));
      if (mask == 0) fix.fail("fixes nothing; list the dofs to fix, e.g. [x, y, z]");
    }
    for (auto i : nodes) b.model.fixed[static_cast<std::size_t>(i)] |= mask;
  }
}

void read_prescribed_velocities(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"name", "nodes", "dof", "value", "curve"});
    model::PrescribedVelocity pv;
    pv.name = e.has("name")
                  ? e.required("name").text()
                  : fmt::format("prescribed_velocity_{}", b.model.prescribed_velocities.size());
    pv.nodes = read_node_reference(e.required("nodes", "a node set name"), b);
    pv.dof = read_dof(e.required("dof", "x, y, z, rx, ry or rz"), true);
    pv.velocity = read_value_or_curve(e, "value");
    b.model.prescribed_velocities.push_back(std::move(pv));
  }
}

void read_loads(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"name", "nodes", "dof", "force", "curve"});
    model::NodalLoad load;
    load.name =
        e.has("name") ? e.required("name").text() : fmt::format("load_{}", b.model.loads.size());
    load.nodes = read_node_reference(e.required("nodes", "a node set name"), b);
    load.dof = read_dof(e.required("dof", "x, y or z"), false);
    load.force = read_value_or_curve(e, "force");
    b.model.loads.push_back(std::move(load));
  }
}

void read_initial_velocities(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"nodes", "part", "velocity"});
    const auto nodes = e.optional("nodes");
    const auto part = e.optional("part");
    if (nodes && part) part->fail("give either 'nodes' or 'part', not both");
    if (!nodes && !part) e.fail("needs 'nodes: <set>' or 'part: <name>'");
    model::InitialVelocity iv;
    iv.nodes = nodes ? read_node_reference(*nodes, b) : b.part_nodes(read_part_reference(*part, b));
    iv.velocity_m_s = e.required("velocity", "[vx, vy, vz] in m/s").vec3();
    b.model.initial_velocities.push_back(std::move(iv));
  }
}

}  // namespace crashlink::io::detail
