#include "solver/deck_writer/deck_writer.h"

#include <fmt/format.h>

#include "solver/deck_writer/composer.h"

namespace crashlink::deck_writer {

namespace detail {

namespace {

// *CONTROL_ENERGY card 1 (the reader takes the keyword without effect, so its layout lives here).
constexpr deck::FieldSpec kControlEnergy[] = {
    {"HGEN", 10}, {"RWEN", 10}, {"SLNTEN", 10}, {"RYLEN", 10}};

/// A YAML double-quoted scalar.
std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + '"';
}

}  // namespace

void list_cards(KeywordBlock& b, const std::vector<std::int64_t>& ids) {
  for (std::size_t k = 0; k < ids.size(); k += 8) {
    std::vector<Value> v;
    for (std::size_t j = k; j < ids.size() && j < k + 8; ++j)
      v.emplace_back(static_cast<long long>(ids[j]));
    b.card(L::kSetList, std::move(v));
  }
}

ExportText Composer::compose(const std::string& deck_name, const std::string& source) {
  check_exportable();
  head(source);
  controls();
  materials();
  parts();
  nodes();
  elements();
  rigid_constraints();
  constraints();
  initial_velocities();
  rigid_body_velocities();
  curve_dofs();
  contacts();
  rigid_walls();
  probes();
  out_ << "*END\n";
  ExportText t;
  t.deck = out_.str();
  t.scenario = scenario(deck_name);
  if (rounding_.rounded > 0)
    notes_.push_back(fmt::format(
        "{} values needed more digits than their columns hold (even in long format) and were "
        "rounded; the largest change: {:.2e} relative ({})",
        rounding_.rounded, rounding_.max_relative, rounding_.worst));
  t.notes = std::move(notes_);
  t.rounding = rounding_;
  return t;
}

void Composer::head(const std::string& source) {
  out_ << "*KEYWORD\n";
  comment(fmt::format("written by crashlink export from {}", source));
  comment(fmt::format("units {}: length {} m, mass {} kg, time {} s", u_.name, u_.length_m,
                      u_.mass_kg, u_.time_s));
  comment("crashlink run reads it back to the model it was written from (docs/decks.md)");
  KeywordBlock t("*TITLE");
  t.line(m_.name);
  emit(t);
}

void Composer::controls() {
  const auto& c = m_.controls;
  KeywordBlock term("*CONTROL_TERMINATION");
  term.card(L::kTermination, {time(c.end_time_s)});
  emit(term);
  KeywordBlock step("*CONTROL_TIMESTEP");
  // DT2MS < 0: the mass scaling the model was read with (MS1ST 1: at the first step, as
  // crashlink computes it); the reader applies it again to the unscaled masses it reads.
  if (c.mass_scaling_dt_s > 0.0)
    step.card(L::kTimestep, {Value(), c.dt_scale, Value(), Value(), -time(c.mass_scaling_dt_s),
                             Value(), Value(), 1});
  else
    step.card(L::kTimestep, {Value(), c.dt_scale});
  emit(step);
  // Q1 quadratic, Q2 linear (LS-DYNA's names); TYPE -2: shells too. Off: both 0 (crashlink reads
  // zeros as written; LS-DYNA may take 0 as its default).
  KeywordBlock bulk("*CONTROL_BULK_VISCOSITY");
  const bool on = c.bulk_viscosity;
  bulk.card(L::kControlBulk, {on ? c.bulk_q_quadratic : 0.0, on ? c.bulk_q_linear : 0.0,
                              c.shell_bulk_viscosity ? -2 : 1});
  emit(bulk);
  if (!on)
    notes_.push_back(
        "bulk viscosity is off: written as Q1 = Q2 = 0 (LS-DYNA may read 0 as its defaults 1.5 "
        "and 0.06)");
  if (!m_.contacts.empty()) {
    // crashlink's penalty scale is each contact's SFS (= SFM) with SLSFAC 1.
    KeywordBlock cc("*CONTROL_CONTACT");
    cc.card(L::kControlContact, {1.0});
    emit(cc);
  }
  // Belytschko-Tsay shells whose thickness follows their thickness strain (crashlink's shells).
  bool shells = false;
  for (const auto& p : m_.parts) shells = shells || p.kind == model::ElementKind::Shell4;
  if (shells) {
    KeywordBlock cs("*CONTROL_SHELL");
    cs.card(L::kControlShell, {Value(), Value(), Value(), 1, 2});
    emit(cs);
  }
  KeywordBlock energy("*CONTROL_ENERGY");  // the energies crashlink accounts for
  energy.card(kControlEnergy, {2, 2, 2, 2});
  emit(energy);
  for (int axis = 0; axis < 3; ++axis) {
    const double g = c.gravity_m_s2[static_cast<std::size_t>(axis)];
    if (g == 0.0) continue;
    // LS-DYNA's base acceleration: gravity g along an axis is the body load -g.
    const double a = -g * u_.time_s * u_.time_s / u_.length_m;
    const std::int64_t id =
        curve({0.0, time(c.end_time_s)}, {a, a}, fmt::format("base acceleration {}", "XYZ"[axis]));
    KeywordBlock lb(fmt::format("*LOAD_BODY_{}", "XYZ"[axis]));
    lb.card(L::kLoadBody, {static_cast<long long>(id), 1.0});
    emit(lb);
  }
  if (c.history_interval_s > 0.0) {
    std::vector<std::string> series{"*DATABASE_GLSTAT", "*DATABASE_MATSUM"};
    if (!m_.contacts.empty()) series.emplace_back("*DATABASE_RCFORC");
    if (!m_.rigid_walls.empty()) series.emplace_back("*DATABASE_RWFORC");
    for (const auto& s : series) {
      KeywordBlock b(s);
      b.card(L::kDatabaseAscii, {time(c.history_interval_s)});
      emit(b);
    }
  }
  if (c.field_interval_s > 0.0) {
    KeywordBlock b("*DATABASE_BINARY_D3PLOT");
    b.card(L::kD3plot, {time(c.field_interval_s)});
    emit(b);
  }
}

std::string Composer::scenario(const std::string& deck_name) const {
  const auto& c = m_.controls;
  const model::Controls defaults;
  std::string controls;
  if (c.dt_max_s > 0.0) controls += fmt::format("  dt_max: {}  # s\n", c.dt_max_s);
  if (c.energy_tolerance != defaults.energy_tolerance)
    controls += fmt::format("  energy_tolerance: {}\n", c.energy_tolerance);
  if (c.bulk_linear_in_expansion) controls += "  bulk_viscosity: {linear_in_expansion: true}\n";
  if (c.global_stable_step) controls += "  stable_step: global\n";
  if (controls.empty() && m_.domains.empty()) return {};
  std::string y = fmt::format(
      "# Written by crashlink export with {0}: the deck holds the model; this scenario adds what "
      "a\n# deck does not say (domains, coupling, crashlink's own controls).\n"
      "name: {1}\nmodel: {{deck: {2}, units: {3}}}\n",
      deck_name, quoted(m_.name), quoted(deck_name), u_.name);
  if (!controls.empty()) y += "controls:\n" + controls;
  if (!m_.domains.empty()) {
    y += "domains:\n";
    for (const auto& d : m_.domains) {
      std::string parts;
      for (int p : d.parts)
        parts += (parts.empty() ? "" : ", ") + quoted(m_.parts[static_cast<std::size_t>(p)].name);
      y += fmt::format("  {}: {{parts: [{}]}}\n", quoted(d.name), parts);
    }
    const auto& idamp = m_.coupling.interface_damping;
    if (idamp.ratio > 0.0)
      y += fmt::format("coupling:\n  interface_damping: {{ratio: {}, layers: {}}}\n", idamp.ratio,
                       idamp.layers);
  }
  return y;
}

}  // namespace detail

ExportText export_deck(const model::Model& m, const deck::UnitSystem& units,
                       const std::string& deck_name, const std::string& source) {
  detail::Composer c(m, units);
  return c.compose(deck_name, source);
}

}  // namespace crashlink::deck_writer
