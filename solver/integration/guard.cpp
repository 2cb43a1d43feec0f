#include "solver/integration/guard.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace crashlink::integration {

namespace {

std::size_t fastest_node(const double* v, std::size_t n) {
  std::size_t best = 0;
  double best_s2 = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double s2 =
        v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2];
    if (s2 > best_s2 || !std::isfinite(s2)) {
      best = i;
      best_s2 = s2;
      if (!std::isfinite(s2)) break;
    }
  }
  return best;
}

}  // namespace

std::string early_stop_hint(const GuardContext& c) {
  if (c.cycle >= kEarlyStopCycles) return "";
  return fmt::format(
      " Stopped within the first {} cycles: check the units of thickness, modulus, density, "
      "velocities (SI: m, Pa, kg/m^3, m/s).",
      kEarlyStopCycles);
}

double guarded_balance_error(const EnergyAccount& e, double floor_J) {
  const double reference = std::max(e.reference_J, floor_J);
  return reference > 0.0 ? e.balance_J() / reference : 0.0;
}

void check_finite_velocities(const model::Model& m, const double* v, const GuardContext& c) {
  const std::size_t n = m.nodes.count();
  for (std::size_t i = 0; i < 3 * n; ++i) {
    if (!std::isfinite(v[i])) {
      throw NumericalError(fmt::format(
          "{}: velocity of node {} is {} at cycle {}, t = {:.6e} s (dt = {:.3e} s). The solution "
          "blew up: check the time step scale (default 0.9 of the stable step), penalty and "
          "hourglass settings, and the elements around this node.{}",
          c.domain, m.nodes.id[i / 3], v[i], c.cycle, c.time_s, c.dt_s, early_stop_hint(c)));
    }
  }
}

double guarded_error(const EnergyAccount& e, double floor_J, double created_J) {
  const double reference = std::max(e.reference_J, floor_J);
  return reference > 0.0 ? (std::abs(e.balance_J()) + created_J) / reference : 0.0;
}

namespace {

/// ": energy balance error B % plus C % created by contacts: contact 'x' created ... J, P % of
/// E0 = R J ..." when contacts created energy, else "": the created part of the message.
std::string created_part(const model::Model& m, const EnergyAccount& e, double reference_J,
                         const ContactCreation& created) {
  if (!(created.total_J != 0.0)) return "";
  const std::string name = created.worst < m.contacts.size() ? m.contacts[created.worst].name
                                                             : fmt::format("#{}", created.worst);
  const std::string others = created.creating > 1
                                 ? fmt::format("; {} interfaces created {:.4g} J in all",
                                               created.creating, created.total_J)
                                 : std::string();
  return fmt::format(
      " (energy balance error {:.3g} % plus {:.3g} % created by contacts: contact '{}' created "
      "{:.4g} J, {:.3g} % of E0 = {:.6g} J{}; the balance books it as negative contact energy, "
      "{:.6g} J in all, and cannot show it)",
      100.0 * e.balance_J() / reference_J, 100.0 * created.total_J / reference_J, name,
      created.worst_J, 100.0 * created.worst_J / reference_J, reference_J, others, e.contact_J);
}

}  // namespace

void check_energy_balance(const model::Model& m, const EnergyAccount& e, const BalanceBound& bound,
                          const double* v, const GuardContext& c, const ContactCreation& created) {
  const double err = guarded_error(e, bound.floor_J, created.total_J);
  const double tolerance = bound.tolerance;
  if (std::isfinite(err) && err <= tolerance) return;
  const double reference = std::max(e.reference_J, bound.floor_J);
  const double balance = guarded_balance_error(e, bound.floor_J);
  const bool by_contact = created.total_J > std::abs(e.balance_J()) || std::isnan(created.total_J);
  const std::size_t i = fastest_node(v, m.nodes.count());
  const double speed =
      std::sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
  const std::string what =
      by_contact
          ? "Energy was created by contact: the run would report it as negative contact "
            "energy."
          : (balance > 0 ? "Energy was created: the run went unstable." : "Energy was lost.");
  const char* likely =
      by_contact
          ? "Likely cause: initial penetrations, a penalty too stiff for the step, or a pairing "
            "the contact handles badly (a fine slave face on a coarse master: swap slave and "
            "master)."
          : "Likely cause: a step above the stable limit (controls.dt_scale), a too stiff "
            "penalty, or an unstable coupling.";
  throw NumericalError(fmt::format(
      "{}: {} {:.3g} %{} exceeds the bound {:.3g} % at cycle {}, t = {:.6e} s (dt = {:.3e} s): "
      "kinetic {:.6e} J, internal {:.6e} J, hourglass {:.6e} J, external work {:.6e} J, initial "
      "{:.6e} J. {} The fastest node is {} ({:.4g} m/s). {}{}",
      c.domain, created.total_J != 0.0 ? "energy error" : "energy balance error",
      100.0 * (created.total_J != 0.0 ? err : balance), created_part(m, e, reference, created),
      100.0 * tolerance, c.cycle, c.time_s, c.dt_s, e.kinetic_J, e.internal_J, e.hourglass_J,
      e.external_work_J, e.initial_total_J, what, m.nodes.id[i], speed, likely,
      early_stop_hint(c)));
}

}  // namespace crashlink::integration
