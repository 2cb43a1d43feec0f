#include "solver/io/scenario_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/errors.h"
#include "solver/deck/model_from_deck.h"
#include "solver/integration/mass_scaling.h"
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

void read_controls(const YamlNode& c, model::Controls& out, bool end_time_required) {
  c.expect_keys({"end_time", "dt_scale", "dt_max", "history_interval", "field_interval",
                 "bulk_viscosity", "energy_tolerance", "gravity", "plausibility_checks",
                 "mass_scaling_dt", "stable_step"});
  if (end_time_required)
    out.end_time_s = c.required("end_time", "simulated time in s, e.g. 0.01").positive();
  else if (auto v = c.optional("end_time"))
    out.end_time_s = v->positive();
  if (auto v = c.optional("dt_scale")) {
    out.dt_scale = v->positive();
    if (out.dt_scale > 1.0)
      v->fail(fmt::format("{} exceeds 1: the step would be above the stable limit; use 0.9",
                          out.dt_scale));
  }
  // Keys not given keep `out`: model::Controls' defaults, or what a deck set.
  out.dt_max_s = c.non_negative_or("dt_max", out.dt_max_s);
  out.history_interval_s = c.non_negative_or("history_interval", out.history_interval_s);
  out.field_interval_s = c.non_negative_or("field_interval", out.field_interval_s);
  if (auto bv = c.optional("bulk_viscosity")) {
    bv->expect_keys({"enabled", "q_linear", "q_quadratic", "shells", "linear_in_expansion"});
    out.bulk_viscosity = bv->boolean_or("enabled", true);
    out.bulk_q_linear = bv->non_negative_or("q_linear", out.bulk_q_linear);
    out.bulk_q_quadratic = bv->non_negative_or("q_quadratic", out.bulk_q_quadratic);
    out.shell_bulk_viscosity = bv->boolean_or("shells", out.shell_bulk_viscosity);
    out.bulk_linear_in_expansion =
        bv->boolean_or("linear_in_expansion", out.bulk_linear_in_expansion);
  }
  out.energy_tolerance = c.positive_or("energy_tolerance", out.energy_tolerance);
  // Conventional mass scaling at t = 0 to this element step [s] (integration/mass_scaling.h;
  // a deck's DT2MS < 0): applied once the model is built.
  out.mass_scaling_dt_s = c.non_negative_or("mass_scaling_dt", out.mass_scaling_dt_s);
  out.gravity_m_s2 = c.vec3_or("gravity", out.gravity_m_s2);
  // `element`: each element's own estimate; `global`: the mesh's highest frequency, by Lanczos
  // on M^-1 K (integration/global_step.h).
  if (auto v = c.optional("stable_step"))
    out.global_stable_step = v->choice({"element", "global"}) == "global";
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

/// `model: {deck, units, ignore}`: the model of a keyword deck, path relative to the scenario
/// file (docs/decks.md "In a scenario"); the files read are appended to `deck_files`.
model::Model read_deck_model(const YamlNode& spec, const std::string& scenario_file,
                             std::vector<std::int64_t>& part_ids,
                             std::vector<std::string>& deck_files) {
  spec.expect_keys({"deck", "units", "ignore"});
  const auto deck_key = spec.required("deck", "the keyword deck's path, relative to this file");
  const std::string written = deck_key.text();
  std::filesystem::path path(written);
  if (path.is_relative()) path = std::filesystem::path(scenario_file).parent_path() / path;
  if (!deck::is_deck_path(path.string()))
    deck_key.fail(fmt::format(
        "'{}' is not a keyword deck (.k, .key, .dyn, .kw); fix: name the deck file", written));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    deck_key.fail(
        fmt::format("cannot open '{}' (looked for {}); fix: give the deck's path "
                    "relative to this scenario file",
                    written, path.string()));
  const auto units_key = spec.required(
      "units", fmt::format("the deck's unit system, one of {}", deck::unit_system_names()));
  const std::string units = units_key.text();
  if (!deck::find_unit_system(units))
    units_key.fail(fmt::format("'{}' is not a unit system; fix: one of {} (docs/decks.md, Units)",
                               units, deck::unit_system_names()));
  deck::DeckOptions options;
  options.mass_scaling = false;  // applied by the scenario once its controls are read
  options.units = units;
  if (auto ig = spec.optional("ignore")) {
    const std::vector<YamlNode> items =
        ig->is_sequence() ? ig->items("keywords without '*'") : std::vector<YamlNode>{*ig};
    for (const auto& k : items) options.ignore.push_back(k.text());
  }
  deck::DeckRead read = deck::read_deck(path.string(), options);
  part_ids = std::move(read.part_ids);
  deck_files.insert(deck_files.end(), read.files.begin(), read.files.end());
  return std::move(read.model);
}

/// controls.mass_scaling_dt (or the deck's DT2MS): the density factors set once, at the line
/// of `controls` for a refusal.
void apply_mass_scaling(const YamlNode& root, model::Model& m, const std::string& file) {
  if (!(m.controls.mass_scaling_dt_s > 0.0)) return;
  try {
    (void)integration::apply_mass_scaling(m);
  } catch (const ModelError& e) {
    const auto c = root.optional("controls");
    throw InputError(file, c ? c->line() : 1, "controls.mass_scaling_dt", e.what());
  }
}

/// A scenario naming a deck: the deck gives the model, the scenario adds `controls` (overrides),
/// `node_sets`, `probes`, `domains` and `coupling`.
model::Model build_deck_scenario(const YamlNode& root, const std::string& name_for_messages,
                                 std::vector<std::string>& deck_files) {
  root.expect_keys({"name", "description", "model", "controls", "node_sets", "probes", "domains",
                    "coupling", "materials", "parts", "boundary", "prescribed_velocity", "loads",
                    "initial_velocity", "rigid_bodies", "rigid_walls", "contacts"});
  for (const char* k : {"materials", "parts", "boundary", "prescribed_velocity", "loads",
                        "initial_velocity", "rigid_bodies", "rigid_walls", "contacts"})
    if (auto v = root.optional(k))
      v->fail(fmt::format(
          "the deck named in `model` defines the {}; a scenario naming a deck adds only name, "
          "description, controls, node_sets, probes, domains and coupling; fix: write it in the "
          "deck or remove it here",
          k));
  detail::ScenarioBuild b;
  b.file = name_for_messages;
  const auto spec = root.required("model", "{deck: file.k, units: mm-t-s}");
  b.model = read_deck_model(spec, name_for_messages, b.deck_part_ids, deck_files);
  if (auto n = root.optional("name")) b.model.name = n->text();
  if (auto d = root.optional("description")) (void)d->text();
  for (std::size_t p = 0; p < b.model.parts.size(); ++p) b.part_line[b.model.parts[p].name] = 0;
  for (std::size_t i = 0; i < b.model.materials.size(); ++i)
    b.material_index[b.model.materials[i].name] = static_cast<int>(i);
  for (std::size_t i = 0; i < b.model.rigid_bodies.size(); ++i)
    b.rigid_body_index[b.model.rigid_bodies[i].name] = static_cast<int>(i);
  if (auto c = root.optional("controls"))
    detail::read_controls(*c, b.model.controls, /*end_time_required=*/false);
  if (auto s = root.optional("node_sets")) detail::read_node_sets(*s, b);
  if (auto s = root.optional("probes")) detail::read_probes(*s, b);
  if (auto s = root.optional("domains")) detail::read_domains(*s, b);
  if (auto s = root.optional("coupling")) detail::read_coupling(*s, b);
  apply_mass_scaling(root, b.model, name_for_messages);
  try {
    model::validate(b.model);
  } catch (const ModelError& e) {
    throw InputError(name_for_messages, spec.line(), "model", e.what());
  }
  return std::move(b.model);
}

model::Model build_model(YamlTree tree, const std::string& name_for_messages,
                         std::vector<std::string>& deck_files) {
  const YamlNode root(std::make_shared<const YamlTree>(std::move(tree)), name_for_messages);
  if (!root.is_map())
    root.fail("a scenario is a mapping of sections (name, controls, materials, parts, ...)");
  if (root.optional("model")) return build_deck_scenario(root, name_for_messages, deck_files);
  root.expect_keys({"name", "description", "model", "controls", "materials", "parts", "node_sets",
                    "boundary", "prescribed_velocity", "loads", "initial_velocity", "rigid_bodies",
                    "rigid_walls", "contacts", "probes", "domains", "coupling"});

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
  if (auto s = root.optional("loads")) detail::read_loads(*s, b);
  if (auto s = root.optional("initial_velocity")) detail::read_initial_velocities(*s, b);
  detail::read_rigid_bodies(root.optional("rigid_bodies"), b);
  // after the bodies: a motion may drive one
  if (auto s = root.optional("prescribed_velocity")) detail::read_prescribed_velocities(*s, b);
  if (auto s = root.optional("rigid_walls")) detail::read_rigid_walls(*s, b);
  if (auto s = root.optional("contacts")) detail::read_contacts(*s, b);
  if (auto s = root.optional("probes")) detail::read_probes(*s, b);
  if (auto s = root.optional("domains")) detail::read_domains(*s, b);
  if (auto s = root.optional("coupling")) detail::read_coupling(*s, b);
  apply_mass_scaling(root, b.model, name_for_messages);

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
  std::vector<std::string> deck_files;
  return build_model(YamlTree::parse(yaml_text, name_for_messages), name_for_messages, deck_files);
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
  std::vector<std::string> deck_files;
  return build_model(
      parse_file(path,
                 "cannot open the scenario file; check the path (scenarios live in scenarios/)"),
      path, deck_files);
}

ScenarioWithHash read_scenario_with_hash(const std::string& path) {
  YamlTree tree = parse_file(path, "cannot open the scenario file; check the path");
  HashOfTree partial = begin_scenario_hash(tree);
  std::vector<std::string> deck_files;
  model::Model model = build_model(std::move(tree), path, deck_files);
  return {std::move(model), finish_scenario_hash(partial, deck_files)};
}

}  // namespace crashlink::io
