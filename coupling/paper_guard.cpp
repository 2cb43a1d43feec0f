// The `paper` scheme's energy guard (paper_guard.h).
#include "coupling/paper_guard.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace crashlink::coupling::paper {

std::optional<std::string> EnergyGuard::sample(double coupled_J, double total_J, double loads_J) {
  if (!std::isfinite(coupled_J)) return fmt::format("the coupled energy is {} J", coupled_J);
  peak_ = std::max({peak_, std::abs(total_J), std::abs(loads_J)});
  if (first_) min_ = coupled_J;
  first_ = false;
  min_ = std::min(min_, coupled_J);
  if (rise_ > 0.0 && peak_ > 0.0 && coupled_J - min_ > rise_ * peak_)
    return fmt::format(
        "the coupled energy (kinetic + internal - external work) rose {:.3g} % of the peak "
        "energy ({:.4e} J) above its running minimum (guard: {:.3g} %)",
        100.0 * (coupled_J - min_) / peak_, peak_, 100.0 * rise_);
  return std::nullopt;
}

std::string unstable_message(const std::string& when, const std::string& what, Drift drift,
                             const std::string& ratio) {
  return fmt::format(
      "paper coupling: the coupling went unstable {}: {}. Scheme `paper` (Bourel 2005 [8]-[11], "
      "drift correction [11] {}), step ratio {}; it is stable only up to a ratio of about 2.3, "
      "and only with bulk viscosity (docs/design.md §2.7; measured in crashlink: r = 2 too can go "
      "unstable, docs/paper-scheme.md). Fix: use the `layer` scheme (the default), or a ratio "
      "below about 2.3 with bulk viscosity on (controls.bulk_viscosity; with its "
      "linear_in_expansion a run at r = 2 lasts far longer)",
      when, what, drift == Drift::on ? "on" : "off", ratio);
}

}  // namespace crashlink::coupling::paper
