#pragma once
// `crashlink export SCENARIO --deck OUT.k [--units U] [--input-units U] [--ignore K,...]`
// (issue #22): the scenario's model written as an LS-DYNA keyword deck (solver/deck_writer) in
// the unit system U (default m-kg-s, crashlink's SI: the deck then reads back bit for bit), for
// `crashlink run OUT.k` or another code. A model with domains, coupling options or controls a
// deck does not hold also gets OUT.yaml beside the deck, a scenario naming it (`crashlink run
// OUT.yaml --mode multi`). SCENARIO may itself be a deck (--input-units, --ignore as `crashlink
// run`'s --units, --ignore). Both files are written whole or not at all (a temporary renamed).
// Output (stdout): the files written, their counts, and notes on what LS-DYNA reads otherwise.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

namespace crashlink::apps {

struct ExportOptions {
  std::string scenario;
  std::string deck;                 ///< the deck to write
  std::string units = "m-kg-s";     ///< the deck's unit system
  std::string input_units;          ///< SCENARIO a deck: its units (empty: inferred)
  std::vector<std::string> ignore;  ///< SCENARIO a deck: keywords to skip
};

CLI::App* add_export_command(CLI::App& app, ExportOptions& options);

/// Writes the deck (and the scenario beside it if needed); returns 0. Bad input throws
/// InputError, a model the deck cannot hold ModelError.
int run_export(const ExportOptions& options, std::FILE* out = stdout);

}  // namespace crashlink::apps
