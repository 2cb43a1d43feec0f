#pragma once
// The energy lines of the end-of-run summary, one implementation for `crashlink run --mode mono`
// (run_single.h print_summary) and the coupled runs (apps/cmd_run_coupled.cpp, from the gathered
// result.h5): the contact energy of every interface, what each one created (energy below zero,
// integration/contact_creation.h) said plainly, and the energy balance with that created energy
// counted as error, since the balance itself books it as negative contact energy and shows none
// of it.
//
// Percentages are of E0 = the balance's reference: the largest energy seen (mono:
// EnergyAccount::reference_J; coupled: gather::balance_reference_J of the gathered glstat), the
// denominator of the "energy balance error" printed beside them.
#include <cstdio>
#include <string>
#include <vector>

namespace crashlink::run {

/// One interface's contact energy at the end of the run [J] (NaN: not known).
struct ContactEnergy {
  std::string name;
  double energy_J = 0.0;
};

struct EnergySummary {
  /// (KE + IE + HG + contact) - (E0 + W) - coupling work at the end [J] (energy.h balance_J)
  double balance_J = 0.0;
  double reference_J = 0.0;             ///< E0 of the percentages [J]
  std::vector<ContactEnergy> contacts;  ///< model.contacts order

  /// Sum over the interfaces of max(0, -energy_J) [J] (an unknown, NaN, energy counts 0).
  double created_J() const;
  /// balance_J / reference_J (0 without a reference).
  double balance_error() const;
  /// (|balance_J| + created_J) / reference_J: the error with the created energy counted (as the
  /// guard counts it, guard.h guarded_error) (0 without a reference).
  double error() const;
  /// 100 x energy / reference_J (0 without a reference) [%].
  double percent_of_reference(double energy_J) const;
};

/// Prints, to `out`:
///   contact energy [J] at the end: 'a' 1.23, 'b' -0.48          (when the model has contacts)
///   contact 'b' created 0.48 J, 0.5 % of E0                      (one line per such interface)
///   energy balance error 0.1300 % of the largest energy (E0 = 96.1 J); ... <tail>
/// where "..." is, with created energy, what the balance hides and the error with it counted,
/// and `tail` is the caller's addition to the balance line (e.g. "; hourglass 2 % of internal").
void print_energy_summary(std::FILE* out, const EnergySummary& s, const std::string& tail = "");

}  // namespace crashlink::run
