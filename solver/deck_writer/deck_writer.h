#pragma once
// A model written as an LS-DYNA keyword deck (issue #22, docs/decks.md "Writing a deck"): the
// keywords the reader (solver/deck) takes, so that `crashlink run` of the deck gives the model
// it was written from, and LS-DYNA or OpenRadioss can run it for a cross-check. What a deck
// cannot say (domains, coupling options, crashlink's own controls) goes into a scenario that
// names the deck.
#include <string>
#include <vector>

#include "solver/deck/units.h"
#include "solver/deck_writer/keyword_block.h"
#include "solver/model/model.h"

namespace crashlink::deck_writer {

struct ExportText {
  std::string deck;  ///< the keyword deck
  /// A scenario naming the deck (`model: {deck, units}`) with the model's domains, coupling
  /// options and the controls a deck does not hold; empty if the deck says everything.
  std::string scenario;
  /// What the user should know: forms LS-DYNA reads otherwise, probes renamed, rounding.
  std::vector<std::string> notes;
  Rounding rounding;
};

/// Writes `m` in `units`; `deck_name` is the deck's file name as the scenario names it,
/// `source` the scenario it came from (a comment). Throws ModelError, naming what and the fix,
/// for what the reader could not read back (a rigid body of several parts, stiffness damping,
/// a step bound, a material the deck keywords do not hold).
ExportText export_deck(const model::Model& m, const deck::UnitSystem& units,
                       const std::string& deck_name, const std::string& source);

}  // namespace crashlink::deck_writer
