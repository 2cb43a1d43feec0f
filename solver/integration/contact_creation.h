#pragma once
// Energy created by contact interfaces (honest energy reporting).
//
// Each interface's contact energy (contact::ContactStep::energy_J) is minus the work its forces
// have done since the start. Frictionless it is the energy of its penalty springs (>= 0 up to the
// step's error); friction only adds to it (dissipation). Below zero, the contact has put energy
// into the model that no spring holds: an initial penetration pushed out, a force computed at one
// configuration and applied at another, a projection that jumps. glstat books that energy as
// negative contact energy, so the balance (KE + IE + HG + contact) - (E0 + W) stays near zero and
// cannot show it. It is therefore counted on its own,
//
//     created_J = sum over interfaces of max(0, -energy_J),
//
// and added to the error the guard bounds (guard.h) and the end-of-run summary reports
// (solver/run/energy_summary.h). An interface that both dissipates by friction and creates by
// its springs shows only the net: the creation beyond its friction work.
#include <cstddef>
#include <span>

#include "solver/contact/contact_interface.h"

namespace crashlink::integration {

/// What one interface with contact energy `contact_energy_J` created: max(0, -energy) [J]
/// (NaN stays NaN: an unknown energy is not reported as none).
inline double created_energy_J(double contact_energy_J) {
  return contact_energy_J >= 0.0 ? 0.0 : -contact_energy_J;
}

/// The energy the interfaces of one solver have created so far.
struct ContactCreation {
  double total_J = 0.0;      ///< sum over the interfaces of created_energy_J [J]
  std::size_t worst = 0;     ///< index (model.contacts order) of the one that created the most
  double worst_J = 0.0;      ///< what that one created [J]; 0: none created anything
  std::size_t creating = 0;  ///< how many interfaces created energy (energy_J < 0)
};

/// The creation of the interfaces `steps` (Solver::contact_steps(): model.contacts order).
ContactCreation contact_creation(std::span<const contact::ContactStep> steps);

}  // namespace crashlink::integration
