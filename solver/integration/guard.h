#pragma once
// The run guard (docs/design.md §7 rule 10): a step that blows up ends the run with an error that
// says what happened, where and when — never with NaN output. Checks run every cycle on quantities
// the integrator computes anyway (kinetic energy, balance), so they cost one comparison each.
#include <cstdint>
#include <string>

#include "solver/integration/contact_creation.h"
#include "solver/integration/energy.h"
#include "solver/model/model.h"

namespace crashlink::integration {

struct GuardContext {
  std::int64_t cycle = 0;
  double time_s = 0.0;
  double dt_s = 0.0;
  std::string domain = "model";
};

/// The energy balance's bound: |balance_J| <= tolerance x max(reference_J, floor_J).
struct BalanceBound {
  double tolerance = 0.05;  ///< Controls::energy_tolerance [-]
  double floor_J = 0.0;     ///< the model's scale under the reference (energy_scale.h) [J]
};

/// A guard stop at a cycle below this is most likely a unit mistake in the input (a thickness in
/// mm, a modulus in GPa): the message says so (early_stop_hint).
inline constexpr std::int64_t kEarlyStopCycles = 10;

/// " Stopped within the first N cycles: check the units ..." when c.cycle < kEarlyStopCycles,
/// else "": ready to append to a guard message.
std::string early_stop_hint(const GuardContext& c);

/// Throws NumericalError if any of v[3n] is not finite, naming the first such node (user id).
void check_finite_velocities(const model::Model& m, const double* v, const GuardContext& c);

/// The balance part of the guard's error: balance_J / max(reference_J, floor_J) (0 while both
/// are 0); signed (> 0: created).
double guarded_balance_error(const EnergyAccount& e, double floor_J);

/// The error the guard bounds: (|balance_J| + created_J) / max(reference_J, floor_J), created_J
/// the energy the contacts created (contact_creation.h), which the balance books as negative
/// contact energy and so cannot see. Lost and created energy do not cancel. >= 0 (or NaN).
double guarded_error(const EnergyAccount& e, double floor_J, double created_J);

/// Throws NumericalError if guarded_error exceeds the tolerance; `v` [3n] locates the node with
/// the largest speed, reported as the likely seat of an instability; `created` (this solver's
/// interfaces, m.contacts order) names the contact that created the most energy, with what it
/// created in J and in % of the reference.
void check_energy_balance(const model::Model& m, const EnergyAccount& e, const BalanceBound& bound,
                          const double* v, const GuardContext& c,
                          const ContactCreation& created = {});

}  // namespace crashlink::integration
