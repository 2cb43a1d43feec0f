#include "solver/run/energy_summary.h"

#include <fmt/format.h>

#include <cmath>

#include "solver/integration/contact_creation.h"

namespace crashlink::run {

double EnergySummary::created_J() const {
  double sum = 0.0;
  for (const ContactEnergy& c : contacts) {
    const double created = integration::created_energy_J(c.energy_J);
    if (created > 0.0) sum += created;  // an unknown (NaN) energy is not counted
  }
  return sum;
}

double EnergySummary::balance_error() const {
  return reference_J > 0.0 ? balance_J / reference_J : 0.0;
}

double EnergySummary::error() const {
  return reference_J > 0.0 ? (std::abs(balance_J) + created_J()) / reference_J : 0.0;
}

double EnergySummary::percent_of_reference(double energy_J) const {
  return reference_J > 0.0 ? 100.0 * energy_J / reference_J : 0.0;
}

void print_energy_summary(std::FILE* out, const EnergySummary& s, const std::string& tail) {
  if (!s.contacts.empty()) {
    std::string line = "contact energy [J] at the end:";
    for (std::size_t k = 0; k < s.contacts.size(); ++k)
      line += std::isnan(s.contacts[k].energy_J)
                  ? fmt::format("{} '{}' n/a", k == 0 ? "" : ",", s.contacts[k].name)
                  : fmt::format("{} '{}' {:.6g}", k == 0 ? "" : ",", s.contacts[k].name,
                                s.contacts[k].energy_J);
    fmt::print(out, "{}\n", line);
    for (const ContactEnergy& c : s.contacts) {
      const double created = integration::created_energy_J(c.energy_J);
      if (!(created > 0.0)) continue;
      fmt::print(out, "contact '{}' created {:.3g} J, {:.3g} % of E0\n", c.name, created,
                 s.percent_of_reference(created));
    }
  }
  std::string balance =
      fmt::format("energy balance error {:.4f} % of the largest energy (E0 = {:.6g} J)",
                  100.0 * s.balance_error(), s.reference_J);
  const double created = s.created_J();
  if (created > 0.0) {
    balance += fmt::format(
        ", which books the energy contacts created as negative contact energy; with the {:.3g} J "
        "they created counted: energy error {:.4f} %",
        created, 100.0 * s.error());
  } else if (!s.contacts.empty()) {
    balance += "; no contact created energy";
  }
  fmt::print(out, "{}{}\n", balance, tail);
}

}  // namespace crashlink::run
