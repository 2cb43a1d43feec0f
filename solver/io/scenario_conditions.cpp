// Boundary conditions, prescribed velocities, loads and initial velocities
// (docs/scenario-format.md).
#include "core/errors.h"
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

std::uint8_t read_fixed_dofs(const YamlNode& fix) {
  std::uint8_t mask = 0;
  if (fix.is_scalar() && fix.text() == "all")
    return model::kUx | model::kUy | model::kUz | model::kRx | model::kRy | model::kRz;
  for (const auto& d : fix.items("degrees of freedom [x, y, z, rx, ry, rz] (or 'all')"))
    mask = static_cast<std::uint8_t>(mask | (1u << read_dof(d, true)));
  if (mask == 0) fix.fail("fixes nothing; list the dofs to fix, e.g. [x, y, z]");
  return mask;
}

void read_boundary(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"nodes", "fix"});
    const auto nodes = read_node_reference(e.required("nodes", "a node set name"), b);
    const std::uint8_t mask = read_fixed_dofs(e.required("fix", "[x, y, z, rx, ry, rz] or all"));
    for (auto i : nodes) b.model.fixed[static_cast<std::size_t>(i)] |= mask;
  }
}

void read_prescribed_velocities(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& e : entries_of(section)) {
    e.expect_keys({"name", "nodes", "rigid_body", "dof", "value", "curve"});
    model::PrescribedVelocity pv;
    pv.name = e.has("name")
                  ? e.required("name").text()
                  : fmt::format("prescribed_velocity_{}", b.model.prescribed_velocities.size());
    // a rigid body's motion (its centre's velocity, its angular velocity about a global axis),
    // or the nodes'
    if (const auto body = e.optional("rigid_body")) {
      if (e.has("nodes")) body->fail("give either `nodes` or `rigid_body`, not both");
      const auto it = b.rigid_body_index.find(body->text());
      if (it == b.rigid_body_index.end())
        body->fail(fmt::format("no rigid body '{}'; define it under `rigid_bodies`", body->text()));
      pv.rigid_body = it->second;
    } else {
      pv.nodes = read_node_reference(e.required("nodes", "a node set name, or rigid_body"), b);
    }
    pv.dof = read_dof(e.required("dof", "x, y, z, rx, ry or rz"), true);
    pv.velocity = read_value_or_curve(e, "value");
    b.model.prescribed_velocities.push_back(std::move(pv));
  }
}

/// rigid_walls: {name: {nodes, point, normal, [edge, length, width], [mass, velocity]} or
/// {nodes, shape: cylinder, point, axis, radius, [length]}} (docs/scenario-format.md).
void read_rigid_walls(const YamlNode& section, ScenarioBuild& b) {
  for (const auto& [name, w] : section.entries("rigid walls (name: {nodes, point, normal, ...})")) {
    w.expect_keys({"nodes", "shape", "point", "normal", "axis", "edge", "length", "width", "radius",
                   "mass", "velocity"});
    model::RigidWall rw;
    rw.name = name;
    rw.nodes = read_node_reference(w.required("nodes", "the node set it stops"), b);
    rw.point_m = w.required("point", "[x, y, z] in m").vec3();
    const std::string shape =
        w.has("shape") ? w.required("shape").choice({"plane", "cylinder"}) : std::string("plane");
    const bool cylinder = shape == "cylinder";
    const auto unit = [&](const char* key, const char* what) {
      const auto n = w.required(key, what);
      const Vec3 v = n.vec3();
      const double len = norm(v);
      if (!(len > 0.0)) n.fail("is the zero vector; give a direction");
      return (1.0 / len) * v;
    };
    static const std::vector<const char*> kPlaneOnly{"normal", "edge", "width", "mass", "velocity"},
        kCylinderOnly{"axis", "radius"};
    for (const char* k : cylinder ? kPlaneOnly : kCylinderOnly)
      if (const auto n = w.optional(k))
        n->fail(fmt::format("does not belong to a {}; fix: remove it", shape));
    if (cylinder) {
      rw.shape = model::RigidWall::Shape::Cylinder;
      rw.normal = unit("axis", "[x, y, z], the cylinder's axis from `point`");
      rw.radius_m = w.required("radius", "in m").positive();
      rw.length_m = w.non_negative_or("length", 0.0);
    } else {
      rw.normal = unit("normal", "[x, y, z], toward the nodes it stops");
      if (w.has("edge") || w.has("length") || w.has("width")) {
        Vec3 e = unit("edge", "[x, y, z], the direction of `length` in the plane");
        if (std::abs(dot(e, rw.normal)) > 1e-6)
          w.required("edge").fail("is not in the wall's plane (normal to `normal`); fix it");
        e = e - dot(e, rw.normal) * rw.normal;
        rw.edge = (1.0 / norm(e)) * e;
        rw.length_m = w.required("length", "in m, along `edge` from `point`").positive();
        rw.width_m = w.required("width", "in m, along normal x edge from `point`").positive();
      }
      if (const auto mass = w.optional("mass")) {
        rw.mass_kg = mass->positive();
        rw.velocity_m_s = w.number_or("velocity", 0.0);
      } else if (const auto v = w.optional("velocity")) {
        v->fail("a moving wall needs its `mass` (kg); fix: give it");
      }
    }
    b.model.rigid_walls.push_back(std::move(rw));
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
    e.expect_keys({"nodes", "part", "velocity", "angular_velocity", "centre"});
    const auto nodes = e.optional("nodes");
    const auto part = e.optional("part");
    if (nodes && part) part->fail("give either 'nodes' or 'part', not both");
    if (!nodes && !part) e.fail("needs 'nodes: <set>' or 'part: <name>'");
    model::InitialVelocity iv;
    iv.nodes = nodes ? read_node_reference(*nodes, b) : b.part_nodes(read_part_reference(*part, b));
    iv.velocity_m_s = e.required("velocity", "[vx, vy, vz] in m/s").vec3();
    // a spin: v_i = velocity + omega x (x_i - centre)
    iv.angular_velocity_rad_s = e.vec3_or("angular_velocity", {0.0, 0.0, 0.0});
    if (const auto c = e.optional("centre")) {
      if (!e.has("angular_velocity"))
        c->fail("is the point of a spin's axis: give `angular_velocity` too, or remove it");
      iv.centre_m = c->vec3();
    }
    b.model.initial_velocities.push_back(std::move(iv));
  }
}

}  // namespace crashlink::io::detail
