#pragma once
// Global energy account (LS-DYNA "glstat" quantities) and the energy balance.
//
// Bookkeeping that is exact for central differences ([2] of Bourel 2005) on a linear system at
// constant step, and O(dt^2)-consistent otherwise:
//   kinetic  KE^n = 1/2 sum m v^{n-1/2} . v^{n+1/2}  (the product form: with IE^n = 1/2 u^n K u^n
//            the sum KE^n + IE^n is conserved exactly by [2]; proof in docs/energy-balance.md)
//   internal IE^{n+1} = IE^n + elements' midpoint-rule stress work over [t^n, t^{n+1}]
//   work     W^{n+1}  = W^n + 1/2 (F^n + F^{n+1}) . (u^{n+1} - u^n) for external loads, gravity
//            and the reactions of prescribed velocities (trapezoid rule, the same order as IE).
//   balance  (KE + IE + HG + contact) - (E^0 + W)  should stay ~ 0; its ratio to the largest
//            energy seen is the error the guard bounds.
#include <algorithm>
#include <cmath>

namespace crashlink::integration {

struct EnergyAccount {
  double kinetic_J = 0.0;
  double internal_J = 0.0;  ///< stress work incl. plastic dissipation and bulk viscosity
  double hourglass_J = 0.0;
  double contact_J = 0.0;
  double external_work_J = 0.0;  ///< loads, gravity, prescribed motions
  double coupling_work_J = 0.0;  ///< work done on this domain by the coupling (link forces,
                                 ///< drift corrections, ghost-node motion); 0 for one domain
  double initial_total_J = 0.0;
  double reference_J = 0.0;  ///< largest |energy| seen: denominator of the balance error

  double total_J() const { return kinetic_J + internal_J + hourglass_J + contact_J; }
  /// Energy created (> 0) or lost (< 0) by the numerics, J.
  double balance_J() const {
    return total_J() - initial_total_J - external_work_J - coupling_work_J;
  }
  /// balance_J / reference_J (0 while nothing has energy yet).
  double balance_error() const { return reference_J > 0.0 ? balance_J() / reference_J : 0.0; }
  /// Adds another domain's terms (not reference_J: the sum's own is taken afterwards).
  void add_terms(const EnergyAccount& x) {
    kinetic_J += x.kinetic_J;
    internal_J += x.internal_J;
    hourglass_J += x.hourglass_J;
    contact_J += x.contact_J;
    external_work_J += x.external_work_J;
    coupling_work_J += x.coupling_work_J;
    initial_total_J += x.initial_total_J;
  }
  void update_reference() {
    reference_J = std::max({reference_J, std::abs(kinetic_J), std::abs(internal_J),
                            std::abs(initial_total_J + external_work_J), std::abs(external_work_J),
                            std::abs(coupling_work_J)});
  }
};

}  // namespace crashlink::integration
