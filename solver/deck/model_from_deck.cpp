#include "solver/deck/model_from_deck.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "core/errors.h"
#include "solver/deck/model_builder.h"
#include "solver/integration/mass_scaling.h"

namespace crashlink::deck {

using detail::Builder;
using detail::wave_speed_m_s;

std::vector<std::string> plausible_unit_systems(const Deck& deck) {
  std::vector<std::string> out;
  for (const auto& u : unit_systems()) {
    bool ok = true;
    for (const auto& m : deck.materials) {
      if (m.type == MaterialType::Rigid) continue;
      const double c = wave_speed_m_s(m, u);
      ok = ok && c >= kMinWaveSpeed_m_s && c <= kMaxWaveSpeed_m_s;
    }
    if (ok) out.emplace_back(u.name);
  }
  return out;
}

std::vector<std::string> inferable_unit_systems(const Deck& deck) {
  std::vector<std::string> out;
  const bool deformable = std::any_of(deck.materials.begin(), deck.materials.end(),
                                      [](const auto& m) { return m.type != MaterialType::Rigid; });
  if (!deformable) return out;
  for (const auto& u : unit_systems()) {
    bool ok = true;
    for (const auto& m : deck.materials) {
      if (m.type == MaterialType::Rigid) continue;
      const double c = wave_speed_m_s(m, u), rho = m.rho * u.density_kg_m3();
      ok = ok && c >= kMinWaveSpeed_m_s && c <= kMaxWaveSpeed_m_s && rho >= kMinDensity_kg_m3 &&
           rho <= kMaxDensity_kg_m3;
    }
    if (ok) out.emplace_back(u.name);
  }
  return out;
}

model::Model model_from_deck(const Deck& deck, const UnitSystem& units) {
  Builder b(deck, units);
  return b.build();
}

DeckRead read_deck(const std::string& path, const DeckOptions& options) {
  ParseOptions po;
  po.ignore = options.ignore;
  const Deck deck = parse_deck(path, po);
  const UnitSystem* units = find_unit_system(options.units);
  std::string inferred;
  if (!units && options.units.empty()) {
    // No system given: the one system in which the materials are crash materials, if one.
    const auto fits = inferable_unit_systems(deck);
    if (fits.size() == 1) {
      units = find_unit_system(fits[0]);
      inferred = fits[0];
    }
  }
  if (!units) {
    const auto fits = plausible_unit_systems(deck);
    const auto strict = inferable_unit_systems(deck);
    std::string fit_text, strict_text;
    for (const auto& f : fits) fit_text += (fit_text.empty() ? "" : ", ") + f;
    for (const auto& f : strict) strict_text += (strict_text.empty() ? "" : ", ") + f;
    throw InputError(
        path, 0, "--units",
        fmt::format("{}; a deck writes no units down{}; fix: pass --units with one of {} (the "
                    "materials' wave speeds fit: {}; their densities too: {})",
                    options.units.empty()
                        ? std::string("not given")
                        : fmt::format("'{}' is not a known system", options.units),
                    options.units.empty()
                        ? std::string(", and no single system makes every material's wave "
                                      "speed and density those of a crash material")
                        : std::string(),
                    unit_system_names(), fit_text.empty() ? std::string("none") : fit_text,
                    strict_text.empty() ? std::string("none") : strict_text));
  }
  Builder b(deck, *units);
  DeckRead out{b.build(), {}, {}, {}, std::string(units->name)};
  if (!inferred.empty())
    out.messages.push_back(fmt::format(
        "units: --units not given; read in {}, the only system in which every material's wave "
        "speed sqrt(E/RO) and density are those of a crash material ([{:.0f}, {:.0f}] m/s, "
        "[{:.0f}, "
        "{:.0f}] kg/m^3); pass --units to choose",
        inferred, kMinWaveSpeed_m_s, kMaxWaveSpeed_m_s, kMinDensity_kg_m3, kMaxDensity_kg_m3));
  // DT2MS: the elements below the step get their density (integration/mass_scaling.h).
  if (options.mass_scaling && out.model.controls.mass_scaling_dt_s > 0.0) {
    try {
      out.messages.push_back(integration::apply_mass_scaling(out.model).summary());
    } catch (const ModelError& e) {
      throw InputError(path, 0, "*CONTROL_TIMESTEP DT2MS", e.what());
    }
  }
  for (std::uint32_t f = 0; f < deck.files.count(); ++f) out.files.push_back(deck.files.name(f));
  for (const PartCard& pc : deck.parts)
    if (std::find(b.empty_parts_.begin(), b.empty_parts_.end(), pc.id) == b.empty_parts_.end())
      out.part_ids.push_back(pc.id);
  // LS-DYNA keeps a shell's thickness unless *CONTROL_SHELL ISTUPD asks; crashlink's shells
  // always take it from the thickness strain (ISTUPD 1).
  const bool shells =
      std::any_of(out.model.parts.begin(), out.model.parts.end(),
                  [](const auto& p) { return p.kind == model::ElementKind::Shell4; });
  if (shells && deck.istupd == 0)
    out.messages.push_back(
        "shells: crashlink updates their thickness from the thickness strain (LS-DYNA's "
        "*CONTROL_SHELL ISTUPD 1); the deck leaves ISTUPD at 0, under which LS-DYNA keeps it: "
        "compare with ISTUPD 1");
  if (!deck.without_effect.empty()) {
    std::string s;
    for (const auto& [k, n] : deck.without_effect) s += (s.empty() ? "" : ", ") + k;
    out.messages.push_back("accepted without effect (crashlink writes its own output): " + s);
  }
  if (deck.history_dt_max > deck.history_dt)
    out.messages.push_back(
        fmt::format("crashlink writes every history at one interval: {:g} s, the smallest DT of {}",
                    out.model.controls.history_interval_s, [&] {
                      std::string s;
                      for (const auto& k : deck.history_dt_keywords)
                        s += (s.empty() ? "" : ", ") + k;
                      return s;
                    }()));
  for (const auto& [k, n] : deck.skipped_cards)
    out.messages.push_back(fmt::format("skipped on request (--ignore): {} ({} cards)", k, n));
  if (b.free_nodes_ > 0)
    out.messages.push_back(
        fmt::format("{} nodes belong to no element and are left out", b.free_nodes_));
  for (auto pid : b.empty_parts_)
    out.messages.push_back(fmt::format("part {} has no element and is left out", pid));
  for (const auto& n : deck.notes) out.messages.push_back(n);
  for (const auto& n : b.d_notes_) out.messages.push_back(n);
  return out;
}

bool is_deck_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".k" || ext == ".key" || ext == ".dyn" || ext == ".kw";
}

}  // namespace crashlink::deck
