// Rigid bodies and probes (docs/scenario-format.md).
#include <cmath>
#include <limits>
#include <set>

#include "core/errors.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io::detail {

namespace {

using materials::MaterialKind;

bool is_rigid_part(const model::Model& m, int p) {
  const auto& part = m.parts[static_cast<std::size_t>(p)];
  return m.materials[static_cast<std::size_t>(part.material)].kind == MaterialKind::Rigid;
}

/// `inertia`: [Ixx, Iyy, Izz] (principal, along x, y, z) or a symmetric 3x3 [[..], [..], [..]].
Mat3 read_inertia(const YamlNode& in) {
  const auto rows = in.items("[Ixx, Iyy, Izz] or a 3x3 matrix, kg m^2");
  Mat3 I{};
  if (rows.size() == 3 && rows[0].is_scalar()) {
    for (std::size_t i = 0; i < 3; ++i) I[i][i] = rows[i].positive();
    return I;
  }
  if (rows.size() != 3)
    in.fail(fmt::format("expected [Ixx, Iyy, Izz] or 3 rows of 3, got {} entries", rows.size()));
  for (std::size_t i = 0; i < 3; ++i) I[i] = rows[i].vec3();
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (std::abs(I[i][j] - I[j][i]) > 1e-12 * (std::abs(I[i][j]) + std::abs(I[j][i]) + 1e-300))
        in.fail(fmt::format("not symmetric: I[{}][{}] = {} but I[{}][{}] = {}", i, j, I[i][j], j, i,
                            I[j][i]));
  for (std::size_t i = 0; i < 3; ++i)
    if (!(I[i][i] > 0.0))
      in.fail(fmt::format("diagonal term I[{}][{}] = {} must be > 0", i, i, I[i][i]));
  return I;
}

}  // namespace

void read_rigid_bodies(const std::optional<YamlNode>& section, ScenarioBuild& b) {
  auto& m = b.model;
  std::vector<std::string> owner(m.parts.size());  // body owning each part
  if (section) {
    for (const auto& [name, body] : section->entries("rigid bodies (name: {parts, ...})")) {
      body.expect_keys({"parts", "nodes", "velocity", "angular_velocity", "mass", "inertia",
                        "centre", "fix", "failure"});
      model::RigidBody rb;
      rb.name = name;
      // `nodes`: extra nodes that follow the body (a nodal rigid body without `parts`), a node
      // set name or a selection such as {part: plate, box: ...}
      if (auto nodes = body.optional("nodes")) rb.nodes = read_node_reference(*nodes, b);
      const auto parts = body.optional("parts");
      if (!parts && rb.nodes.empty())
        body.fail("give its rigid `parts`, or the `nodes` that follow it (a nodal rigid body)");
      if (parts)
        for (const auto& pn : parts->items("part names")) {
          const int p = read_part_reference(pn, b);
          if (!is_rigid_part(m, p))
            pn.fail(
                "part '" + pn.text() + "' has material '" +
                m.materials[static_cast<std::size_t>(m.parts[static_cast<std::size_t>(p)].material)]
                    .name +
                "', which is not rigid; give it a material of type rigid");
          auto& o = owner[static_cast<std::size_t>(p)];
          if (!o.empty())
            pn.fail("part '" + pn.text() + "' already belongs to rigid body '" + o +
                    "'; a part belongs to one body");
          o = name;
          rb.parts.push_back(p);
        }
      if (parts && rb.parts.empty()) parts->fail("lists no part; give at least one rigid part");
      rb.velocity_m_s = body.vec3_or("velocity", {0.0, 0.0, 0.0});
      rb.angular_velocity_rad_s = body.vec3_or("angular_velocity", {0.0, 0.0, 0.0});
      if (auto mass = body.optional("mass")) rb.mass_kg = mass->positive();
      if (auto in = body.optional("inertia")) {
        rb.inertia_given = true;
        rb.inertia_kg_m2 = read_inertia(*in);
      }
      if (auto c = body.optional("centre")) {
        rb.centre_given = true;
        rb.centre_m = c->vec3();
      }
      // held: its centre's translations and its rotations about the global axes
      if (auto f = body.optional("fix")) rb.fixed = read_fixed_dofs(*f);
      // a spot weld's failure (LS-DYNA *CONSTRAINED_SPOTWELD SN SS N M TF): a body of two nodes
      if (auto f = body.optional("failure")) {
        f->expect_keys({"normal", "shear", "exp_n", "exp_m", "time"});
        if (parts || rb.nodes.size() != 2)
          f->fail(
              fmt::format("belongs to a spot weld: a body of two `nodes` and no `parts` (it "
                          "has {} nodes{}); fix: select the weld's two nodes",
                          rb.nodes.size(), parts ? " and parts" : ""));
        rb.failure.normal_N = f->non_negative_or("normal", 0.0);
        rb.failure.shear_N = f->non_negative_or("shear", 0.0);
        rb.failure.exp_n = f->positive_or("exp_n", 2.0);
        rb.failure.exp_m = f->positive_or("exp_m", 2.0);
        rb.failure.time_s = f->non_negative_or("time", 0.0);
        if (!rb.failure.any()) f->fail("gives no strength and no time; fix: give one of them");
      }
      b.rigid_body_index[name] = static_cast<int>(m.rigid_bodies.size());
      m.rigid_bodies.push_back(std::move(rb));
    }
  }
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    if (is_rigid_part(m, static_cast<int>(p)) && owner[p].empty())
      throw InputError(b.file, b.part_line.at(m.parts[p].name), "parts." + m.parts[p].name,
                       "has a rigid material but belongs to no rigid body; add it to "
                       "'rigid_bodies: {name: {parts: [" +
                           m.parts[p].name + "]}}'");
}

void read_probes(const YamlNode& section, ScenarioBuild& b) {
  const auto& m = b.model;
  std::set<std::string> deck_probes;  // those a named deck defined (none for a YAML scene)
  for (const auto& p : m.probes) deck_probes.insert(p.name);
  for (const auto& [name, pr] : section.entries("probes (name: {node | node_near | rigid_body})")) {
    pr.expect_keys({"node", "node_near", "part", "rigid_body"});
    model::Probe probe;
    probe.name = name;
    // A deck's *DATABASE_RBDOUT probes every rigid body under its name; a scenario probe of a
    // body replaces that one (whatever its name).
    if (const auto body = pr.optional("rigid_body")) {
      const auto it = b.rigid_body_index.find(body->text());
      if (it != b.rigid_body_index.end())
        std::erase_if(b.model.probes, [&](const model::Probe& p) {
          return p.kind == model::Probe::Kind::RigidBody && p.index == it->second &&
                 deck_probes.count(p.name) > 0;
        });
    }
    for (const auto& other : m.probes)
      if (other.name == name)
        pr.fail(
            fmt::format("a probe '{}' is already defined (a deck's *DATABASE_HISTORY_NODE "
                        "names its probes node_<NID> or by their heading); fix: give this one "
                        "another name",
                        name));
    const auto node = pr.optional("node");
    const auto near = pr.optional("node_near");
    const auto body = pr.optional("rigid_body");
    if ((node ? 1 : 0) + (near ? 1 : 0) + (body ? 1 : 0) != 1)
      pr.fail("give exactly one of 'node: id', 'node_near: [x, y, z]' or 'rigid_body: name'");
    if (auto part = pr.optional("part"); part && !near)
      part->fail("'part' only narrows 'node_near'; remove it");
    if (node) {
      probe.kind = model::Probe::Kind::Node;
      probe.index = m.node_index(node->integer());
      if (probe.index < 0)
        node->fail(
            fmt::format("node id {} is not in the model; use node_near: [x, y, z] to pick "
                        "a node by position",
                        node->integer()));
    } else if (near) {
      probe.kind = model::Probe::Kind::Node;
      const Vec3 x = near->vec3();
      std::vector<std::int32_t> candidates;
      if (auto part = pr.optional("part"))
        candidates = b.part_nodes(read_part_reference(*part, b));
      else
        for (std::size_t i = 0; i < m.nodes.count(); ++i)
          candidates.push_back(static_cast<std::int32_t>(i));
      double best = std::numeric_limits<double>::infinity();
      for (auto i : candidates) {
        const auto k = static_cast<std::size_t>(i);
        const Vec3 y{m.nodes.x0[3 * k], m.nodes.x0[3 * k + 1], m.nodes.x0[3 * k + 2]};
        const double d = norm(y - x);
        if (d < best) {
          best = d;
          probe.index = i;
        }
      }
    } else {
      probe.kind = model::Probe::Kind::RigidBody;
      const std::string bn = body->text();
      const auto it = b.rigid_body_index.find(bn);
      if (it == b.rigid_body_index.end())
        body->fail("unknown rigid body '" + bn + "';" + did_you_mean(bn, b.rigid_body_names()) +
                   " define it under 'rigid_bodies'");
      probe.index = it->second;
    }
    b.model.probes.push_back(std::move(probe));
  }
}

}  // namespace crashlink::io::detail
