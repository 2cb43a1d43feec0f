#pragma once
// The `paper` scheme's energy guard (docs/design.md §7 rule 10, §2.7): at every instant where all
// coupled domains stand together, the coupled energy not explained by the loads,
//   E = sum_k (KE + IE + HG + contact)_k - KE of the coupled nodes counted twice - external work
//     (= initial energy + net work of the link and drift corrections),
// is compared with its running minimum; a rise above `rise` x the peak energy means the coupling
// pumps energy in: the scheme went unstable. Shared by cosim::PaperRunner (one process) and the
// coordinator (processes), so both stop a run at the same instant for the same reason.
#include <optional>
#include <string>

#include "coupling/paper_coupling.h"

namespace crashlink::coupling::paper {

class EnergyGuard {
 public:
  /// rise: fraction of the peak energy (<= 0: no energy check; non-finite E always fails).
  explicit EnergyGuard(double rise = 0.05) : rise_(rise) {}

  /// One sample. coupled_J: E above; total_J: the summed KE + IE + HG + contact (twice-counted
  /// KE removed); loads_J: initial total + external work (the peak is the largest of |total_J|
  /// and |loads_J| seen). Returns what went wrong (for "the coupling went unstable: ...") or
  /// nothing.
  std::optional<std::string> sample(double coupled_J, double total_J, double loads_J);

  double peak_J() const { return peak_; }
  double minimum_J() const { return min_; }
  bool started() const { return !first_; }

 private:
  double rise_;
  double min_ = 0.0, peak_ = 0.0;
  bool first_ = true;
};

/// "paper coupling: the coupling went unstable <when>: <what>. Scheme `paper` (...), step ratio
/// <ratio>; it is stable only up to ... Fix: ..." - the one message of a `paper` run stopped by the
/// guard or by a non-finite acceleration, in one process or over processes.
std::string unstable_message(const std::string& when, const std::string& what, Drift drift,
                             const std::string& ratio);

}  // namespace crashlink::coupling::paper
