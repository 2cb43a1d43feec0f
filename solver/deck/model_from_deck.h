#pragma once
// A keyword deck -> model::Model in SI units: ids resolved (nodes, parts, sections, materials,
// curves, sets), units converted, each rigid part made a rigid body, wave speeds checked. Every
// mistake throws InputError at the card and field it comes from (docs/decks.md).
#include <cstdint>
#include <string>
#include <vector>

#include "solver/deck/deck.h"
#include "solver/deck/units.h"
#include "solver/model/model.h"

namespace crashlink::deck {

struct DeckOptions {
  std::string units;                ///< a name of unit_systems(); empty: refused with candidates
  std::vector<std::string> ignore;  ///< keywords to skip (ParseOptions::ignore)
  /// Apply DT2MS (integration::apply_mass_scaling) and report it; false: the caller does, once
  /// its own controls are known (a scenario naming the deck may change mass_scaling_dt).
  bool mass_scaling = true;
};

struct DeckRead {
  model::Model model;
  /// What the user should see before the run: keywords without effect, keywords skipped on
  /// request (with their card counts), LS-DYNA defaults read differently.
  std::vector<std::string> messages;
  /// Every file read, the deck first then its *INCLUDEs in the order met (paths as opened): what
  /// a scenario naming the deck hashes (io/scenario_hash.h).
  std::vector<std::string> files;
  /// The *PART PID of each model part (model.parts order): `domains:` by part id.
  std::vector<std::int64_t> part_ids;
  std::string units;  ///< the unit system read in (given, or inferred when not given)
};

/// parse_deck, then model_from_deck in the units of `options`.
DeckRead read_deck(const std::string& path, const DeckOptions& options);

/// The model of a parsed deck, converted from `units` to SI; passed through model::validate.
model::Model model_from_deck(const Deck& deck, const UnitSystem& units);

/// The unit systems in which every deformable material's wave speed sqrt(E / rho) lies in
/// [100, 20000] m/s (all of them if the deck has no deformable material).
std::vector<std::string> plausible_unit_systems(const Deck& deck);

/// Wave speeds a crash material has [m/s]: soft foams ~100, steel 5200, beryllium 12 900.
inline constexpr double kMinWaveSpeed_m_s = 100.0;
inline constexpr double kMaxWaveSpeed_m_s = 20000.0;
/// Densities a crash material has [kg/m^3]: foams and honeycombs from ~20, tungsten 19 300.
inline constexpr double kMinDensity_kg_m3 = 10.0;
inline constexpr double kMaxDensity_kg_m3 = 25000.0;

/// The unit systems in which every deformable material has a crash material's wave speed and
/// density (the ranges above): what read_deck infers when no system is given, if there is
/// exactly one (none if the deck has no deformable material). The density separates the systems
/// whose wave speeds agree (m-kg-s and mm-g-ms both read sqrt(E/RO) in m/s).
std::vector<std::string> inferable_unit_systems(const Deck& deck);

/// True if a file name looks like a keyword deck (.k, .key, .dyn, .kw; any case).
bool is_deck_path(const std::string& path);

}  // namespace crashlink::deck
