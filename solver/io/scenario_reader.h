#pragma once
// Scenario files (YAML, SI units) -> model::Model. The format is documented key by key in
// docs/scenario-format.md. Every mistake in the input throws crashlink::InputError whose message
// is "file:line: key.path: what; fix" (1-based line); nothing is returned from bad input.
#include <string>

#include "solver/model/model.h"

namespace crashlink::io {

/// Reads and checks the scenario file at `path`, generates its meshes and returns the model
/// (already passed through model::validate).
model::Model read_scenario(const std::string& path);

/// read_scenario and scenario_hash (scenario_hash.h) of the file, from one parse: what every
/// process of a multi-domain run needs (a failure to open the file says so as scenario_hash).
struct ScenarioWithHash {
  model::Model model;
  std::string hash;
};
ScenarioWithHash read_scenario_with_hash(const std::string& path);

/// Same as read_scenario, from YAML text; `name_for_messages` stands for the file name in error
/// messages and is the model's default name. A scenario naming a keyword deck (`model: {deck:
/// car.k, units: mm-t-s}`, docs/decks.md "In a scenario") reads the deck from disk, its path
/// relative to the folder of `name_for_messages` (read_scenario: of the scenario file).
model::Model parse_scenario(const std::string& yaml_text, const std::string& name_for_messages);

}  // namespace crashlink::io
