#pragma once
// The run guard (DESIGN.md §7 rule 10): a step that blows up ends the run with an error that says
// what happened, where and when — never with NaN output. Checks run every cycle on quantities the
// integrator computes anyway (kinetic energy, balance), so they cost one comparison each.
#include <cstdint>
#include <string>

#include "solver/integration/energy.h"
#include "solver/model/model.h"

namespace crashlink::integration {

struct GuardContext {
  std::int64_t cycle = 0;
  double time_s = 0.0;
  double dt_s = 0.0;
  std::string domain = "model";
};

/// Throws NumericalError if any of v[3n] is not finite, naming the first such node (user id).
void check_finite_velocities(const model::Model& m, const double* v, const GuardContext& c);

/// Throws NumericalError if |balance error| exceeds the tolerance; `v` [3n] locates the node
/// with the largest speed, reported as the likely seat of the instability.
void check_energy_balance(const model::Model& m, const EnergyAccount& e, double tolerance,
                          const double* v, const GuardContext& c);

}  // namespace crashlink::integration
