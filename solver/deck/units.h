#pragma once
// The unit systems of keyword decks (a deck writes none down) and their factors to SI.
#include <string>
#include <string_view>
#include <vector>

namespace crashlink::deck {

struct UnitSystem {
  std::string_view name;  ///< e.g. "mm-t-s"
  double length_m;        ///< one length unit in m
  double mass_kg;         ///< one mass unit in kg
  double time_s;          ///< one time unit in s

  double density_kg_m3() const { return mass_kg / (length_m * length_m * length_m); }
  double stress_Pa() const { return mass_kg / (length_m * time_s * time_s); }
  double velocity_m_s() const { return length_m / time_s; }
  double force_N() const { return mass_kg * length_m / (time_s * time_s); }
};

/// mm-t-s, m-kg-s, mm-kg-ms, mm-g-ms, cm-g-us, in-lbf-s (force lbf: mass lbf s^2/in).
const std::vector<UnitSystem>& unit_systems();
/// The system called `name`, or nullptr.
const UnitSystem* find_unit_system(std::string_view name);
/// "mm-t-s, m-kg-s, ..." for messages.
std::string unit_system_names();

}  // namespace crashlink::deck
