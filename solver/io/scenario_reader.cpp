#include "solver/io/scenario_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>

#include "solver/core/errors.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io {

namespace detail {

namespace {

template <class Map>
std::vector<std::string> keys_of(const Map& m) {
  std::vector<std::string> k;
  for (const auto& kv : m) k.push_back(kv.first);
  return k;
}

}  // namespace

std::vector<std::string> ScenarioBuild::material_names() const {
  return keys_of(material_index);
}
std::vector<std::string> ScenarioBuild::part_names() const {
  return keys_of(part_line);
}
std::vector<std::string> ScenarioBuild::node_set_names() const {
  return keys_of(node_sets);
}
std::vector<std::string> ScenarioBuild::rigid_body_names() const {
  return keys_of(rigid_body_index);
}

std::vector<std::int32_t> ScenarioBuild::part_nodes(int p) const {
  std::vector<std::int32_t> n = model.parts[static_cast<std::size_t>(p)].connectivity;
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

void read_controls(const YamlNode& c, model::Controls& out) {
  c.expect_keys({"end_time", "dt_scale", "dt_max", "history_interval", "field_interval",
                 "bulk_viscosity", "energy_tolerance", "gravity", "plausibility_checks"});
  out.end_time_s = c.required("end_time", "simulated time in s, e.g. 0.01").positive();
  if (auto v = c.optional("dt_scale")) {
    out.dt_scale = v->positive();
    if (out.dt_scale > 1.0)
      v->fail(fmt::format("{} exceeds 1: the step would be above the stable limit; use 0.9",
                          out.dt_scale));
  }
  out.dt_max_s = c.non_negative_or("dt_max", 0.0);
  out.history_interval_s = c.non_negative_or("history_interval", 0.0);
  out.field_interval_s = c.non_negative_or("field_interval", 0.0);
  if (auto bv = c.optional("bulk_viscosity")) {
    bv->expect_keys({"enabled", "q_linear", "q_quadratic", "shells", "linear_in_expansion"});
    out.bulk_viscosity = bv->boolean_or("enabled", true);
    out.bulk_q_linear = bv->non_negative_or("q_linear", 0.06);
    out.bulk_q_quadratic = bv->non_negative_or("q_quadratic", 1.5);
    out.shell_bulk_viscosity = bv->boolean_or("shells", false);
    out.bulk_linear_in_expansion = bv->boolean_or("linear_in_expansion", false);
  }
  out.energy_tolerance = c.positive_or("energy_tolerance", 0.05);
  out.gravity_m_s2 = c.vec3_or("gravity", {0.0, 0.0, 0.0});
}

namespace {

/// `coupling: {interface_damping: {ratio, layers}}` (docs/scenario-format.md "coupling"):
/// options of the coupling between domains, so it needs a `domains` section.
void read_coupling(const YamlNode& c, ScenarioBuild& b) {
  c.expect_keys({"interface_damping"});
  if (b.model.domains.empty())
    c.fail(
        "has no effect without a `domains` section (a single-domain run has no interface); "
        "add `domains` or remove `coupling`");
  if (auto d = c.optional("interface_damping")) {
    d->expect_keys({"ratio", "layers"});
    auto& out = b.model.coupling.interface_damping;
    const auto ratio = d->required("ratio", "fraction of critical damping, e.g. 0.06");
    out.ratio = ratio.non_negative();
    if (out.ratio > 0.5)
      ratio.fail(
          fmt::format("{} exceeds 0.5: the stable step would fall below 0.62 of the undamped "
                      "one; use e.g. 0.06",
                      out.ratio));
    if (auto l = d->optional("layers")) out.layers = l->positive_int();
  }
}

}  // namespace

}  // namespace detail

namespace {

model::Model build_model(YamlTree tree, const std::string& name_for_messages) {
  const YamlNode root(std::make_shared<const YamlTree>(std::move(tree)), name_for_messages);
  if (!root.is_map())
    root.fail("a scenario is a mapping of sections (name, controls, materials, parts, ...)");
  root.expect_keys({"name", "description", "controls", "materials", "parts", "node_sets",
                    "boundary", "prescribed_velocity", "loads", "initial_velocity", "rigid_bodies",
                    "contacts", "probes", "domains", "coupling"});

  detail::ScenarioBuild b;
  b.file = name_for_messages;
  if (auto n = root.optional("name")) {
    b.model.name = n->text();
  } else {
    b.model.name = std::filesystem::path(name_for_messages).stem().string();
  }
  if (auto d = root.optional("description")) (void)d->text();
  detail::read_controls(root.required("controls", "at least end_time in s"), b.model.controls);
  detail::read_materials(root.required("materials", "name: {type, density, ...}"), b);
  detail::read_parts(root.required("parts", "name: {material, mesh: {generator, ...}}"), b);
  b.model.fixed.assign(b.model.nodes.count(), 0);
  if (auto s = root.optional("node_sets")) detail::read_node_sets(*s, b);
  if (auto s = root.optional("boundary")) detail::read_boundary(*s, b);
  if (auto s = root.optional("prescribed_velocity")) detail::read_prescribed_velocities(*s, b);
  if (auto s = root.optional("loads")) detail::read_loads(*s, b);
  if (auto s = root.optional("initial_velocity")) detail::read_initial_velocities(*s, b);
  detail::read_rigid_bodies(root.optional("rigid_bodies"), b);
  if (auto s = root.optional("contacts")) detail::read_contacts(*s, b);
  if (auto s = root.optional("probes")) detail::read_probes(*s, b);
  if (auto s = root.optional("domains")) detail::read_domains(*s, b);
  if (auto s = root.optional("coupling")) detail::read_coupling(*s, b);

  try {
    model::validate(b.model);
  } catch (const ModelError& e) {
    // The section readers check everything with a line number first; this is the safety net.
    throw InputError(name_for_messages, 1, "(model)", e.what());
  }
  if (root.required("controls").boolean_or("plausibility_checks", true))
    detail::check_plausibility(root, b);
  return std::move(b.model);
}

}  // namespace

model::Model parse_scenario(const std::string& yaml_text, const std::string& name_for_messages) {
  return build_model(YamlTree::parse(yaml_text, name_for_messages), name_for_messages);
}

namespace {

/// The file parsed as it is read: its text is never held whole.
YamlTree parse_file(const std::string& path, const std::string& cannot_open) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "(file)", cannot_open);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return YamlTree::parse(in, ec ? 0 : static_cast<std::size_t>(bytes), path);
}

}  // namespace

model::Model read_scenario(const std::string& path) {
  return build_model(
      parse_file(path,
                 "cannot open the scenario file; check the path (scenarios live in scenarios/)"),
      path);
}

ScenarioWithHash read_scenario_with_hash(const std::string& path) {
  YamlTree tree = parse_file(path, "cannot open the scenario file; check the path");
  std::string hash = scenario_hash_of_tree(tree);
  return {build_model(std::move(tree), path), std::move(hash)};
}

}  // namespace crashlink::io
