#pragma once
// Internal to the scenario reader: the model under construction and one reader per top-level
// section (scenario_<section>.cpp). Each reader checks its section completely and throws
// InputError at the offending key; the sections are read in the order declared here, so a
// section may refer to names defined by the ones before it.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "solver/io/yaml_node_access.h"
#include "solver/model/model.h"

namespace crashlink::io::detail {

struct ScenarioBuild {
  std::string file;  ///< for messages
  model::Model model;
  std::map<std::string, int> material_index;                   ///< name -> index in model.materials
  std::map<std::string, int> part_line;                        ///< part name -> line of its key
  std::map<std::string, std::vector<std::int32_t>> node_sets;  ///< name -> sorted node indices
  std::map<std::string, int> rigid_body_index;
  /// A scenario naming a keyword deck (`model: {deck: ...}`): the *PART PID of each model part,
  /// so that a part may be referred to by id as well as by title; empty for YAML parts.
  std::vector<std::int64_t> deck_part_ids;

  std::vector<std::string> material_names() const;
  std::vector<std::string> part_names() const;
  std::vector<std::string> node_set_names() const;
  std::vector<std::string> rigid_body_names() const;
  /// Sorted unique node indices of part `p`.
  std::vector<std::int32_t> part_nodes(int p) const;
};

/// `controls`; keys not given keep the values in `out` (the defaults, or what a deck set).
/// `end_time` is required unless `end_time_required` is false (a deck's *CONTROL_TERMINATION).
void read_controls(const YamlNode& controls, model::Controls& out, bool end_time_required = true);
void read_materials(const YamlNode& materials, ScenarioBuild& b);
void read_parts(const YamlNode& parts, ScenarioBuild& b);
void read_node_sets(const YamlNode& node_sets, ScenarioBuild& b);
void read_boundary(const YamlNode& boundary, ScenarioBuild& b);
void read_prescribed_velocities(const YamlNode& list, ScenarioBuild& b);
void read_loads(const YamlNode& list, ScenarioBuild& b);
void read_initial_velocities(const YamlNode& list, ScenarioBuild& b);
/// Also checks that every part of rigid material belongs to a body (so it runs even if absent).
void read_rigid_bodies(const std::optional<YamlNode>& bodies, ScenarioBuild& b);
void read_rigid_walls(const YamlNode& walls, ScenarioBuild& b);
/// `fix`: [x, y, z, rx, ry, rz] (any of them) or all, as DofBits.
std::uint8_t read_fixed_dofs(const YamlNode& fix);
void read_contacts(const YamlNode& contacts, ScenarioBuild& b);
void read_probes(const YamlNode& probes, ScenarioBuild& b);
void read_domains(const YamlNode& domains, ScenarioBuild& b);
/// After every section: refuses values implausible for their neighbours, likely unit mistakes
/// (scenario_plausibility.cpp; off with controls.plausibility_checks: false).
void check_plausibility(const YamlNode& root, const ScenarioBuild& b);

/// A node selection: a mapping {part, box: {min, max}} or {nodes: [ids]} (see node_sets in
/// docs/scenario-format.md). Fails if it selects no node.
std::vector<std::int32_t> read_selection(const YamlNode& sel, const ScenarioBuild& b);
/// The value of a `nodes:` key: a node set name, or an inline selection mapping.
std::vector<std::int32_t> read_node_reference(const YamlNode& ref, const ScenarioBuild& b);
/// A part name that must exist (or, for a deck, its *PART PID); returns its index.
int read_part_reference(const YamlNode& ref, const ScenarioBuild& b);
/// A degree of freedom x, y, z (0-2) or, if rotations are allowed, rx, ry, rz (3-5).
int read_dof(const YamlNode& dof, bool rotations);
/// A function of time: either `<constant_key>: number` or `curve: {t: [...], v: [...]}` under
/// `entry` (exactly one of the two).
model::Curve read_value_or_curve(const YamlNode& entry, const std::string& constant_key);

}  // namespace crashlink::io::detail
