#include "solver/deck/units.h"

namespace crashlink::deck {

namespace {

constexpr double kInch_m = 0.0254;
constexpr double kPoundForce_N = 4.4482216152605;

}  // namespace

const std::vector<UnitSystem>& unit_systems() {
  static const std::vector<UnitSystem> all = {
      {"mm-t-s", 1e-3, 1e3, 1.0},
      {"m-kg-s", 1.0, 1.0, 1.0},
      {"mm-kg-ms", 1e-3, 1.0, 1e-3},
      {"mm-g-ms", 1e-3, 1e-3, 1e-3},
      {"cm-g-us", 1e-2, 1e-3, 1e-6},
      // lbf s^2 / in: the mass a pound-force accelerates at one inch per second squared
      {"in-lbf-s", kInch_m, kPoundForce_N / kInch_m, 1.0},
  };
  return all;
}

const UnitSystem* find_unit_system(std::string_view name) {
  for (const auto& u : unit_systems())
    if (u.name == name) return &u;
  return nullptr;
}

std::string unit_system_names() {
  std::string s;
  for (const auto& u : unit_systems()) s += (s.empty() ? "" : ", ") + std::string(u.name);
  return s;
}

}  // namespace crashlink::deck
