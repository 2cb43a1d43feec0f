#include "apps/cmd_export.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "solver/deck/model_from_deck.h"
#include "solver/deck_writer/deck_writer.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::apps {

namespace {

/// Writes `text` to `path` through a temporary beside it: the file is whole or absent.
void write_whole(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    f.flush();
    if (!f)
      throw InputError(
          fmt::format("export: cannot write {}; fix: a writable folder with space", tmp.string()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(fmt::format("export: cannot write {}: {}", path.string(), ec.message()));
  }
}

}  // namespace

CLI::App* add_export_command(CLI::App& app, ExportOptions& options) {
  auto* cmd = app.add_subcommand(
      "export", "write a scenario's model as an LS-DYNA keyword deck (and a scenario naming it)");
  cmd->add_option("scenario", options.scenario, "scenario YAML file, or a keyword deck")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--deck", options.deck, "the keyword deck to write (.k)")->required();
  cmd->add_option("--units", options.units,
                  "the deck's unit system: " + deck::unit_system_names() +
                      " (m-kg-s: the values as crashlink holds them, read back bit for bit)")
      ->capture_default_str();
  cmd->add_option("--input-units", options.input_units,
                  "SCENARIO a keyword deck: its unit system (inferred if not given)");
  cmd->add_option("--ignore", options.ignore, "SCENARIO a keyword deck: keywords to skip")
      ->delimiter(',');
  return cmd;
}

int run_export(const ExportOptions& o, std::FILE* out) {
  const deck::UnitSystem* units = deck::find_unit_system(o.units);
  if (!units)
    throw InputError(fmt::format("export: --units {} is not a unit system; fix: one of {}", o.units,
                                 deck::unit_system_names()));
  const std::filesystem::path deck_path(o.deck);
  if (!deck::is_deck_path(deck_path.string()))
    throw InputError(fmt::format(
        "export: --deck {} does not end in .k, .key, .dyn or .kw; fix: name it e.g. model.k",
        o.deck));
  const model::Model m = deck::is_deck_path(o.scenario)
                             ? deck::read_deck(o.scenario, {o.input_units, o.ignore}).model
                             : io::read_scenario(o.scenario);
  const auto text = deck_writer::export_deck(m, *units, deck_path.filename().string(),
                                             std::filesystem::path(o.scenario).filename().string());
  auto yaml = deck_path;
  yaml.replace_extension(".yaml");
  std::error_code ec;
  for (const auto& out_path : {deck_path, yaml})
    if ((out_path == deck_path || !text.scenario.empty()) && std::filesystem::exists(out_path) &&
        std::filesystem::equivalent(out_path, o.scenario, ec))
      throw InputError(fmt::format(
          "export: writing {} would overwrite the scenario being exported; fix: name the deck "
          "otherwise (--deck {}_deck.k)",
          out_path.string(), deck_path.stem().string()));
  write_whole(deck_path, text.deck);
  std::size_t elements = 0;
  for (const auto& p : m.parts) elements += p.element_count();
  std::fprintf(out,
               "crashlink export: %s: %zu nodes, %zu elements, %zu parts, %zu contacts, units %s\n",
               o.deck.c_str(), m.nodes.count(), elements, m.parts.size(), m.contacts.size(),
               o.units.c_str());
  if (!text.scenario.empty()) {
    write_whole(yaml, text.scenario);
    std::fprintf(out,
                 "crashlink export: %s: the scenario naming the deck, with what a deck does not "
                 "hold (%zu domains); run it with `crashlink run %s%s`\n",
                 yaml.string().c_str(), m.domains.size(), yaml.string().c_str(),
                 m.domains.empty() ? "" : " --mode multi");
  }
  for (const auto& n : text.notes) std::fprintf(out, "crashlink export: note: %s\n", n.c_str());
  return 0;
}

}  // namespace crashlink::apps
