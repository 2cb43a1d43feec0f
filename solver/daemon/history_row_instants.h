#pragma once
// Which coarse instants the history rows of a daemon read the lts energy at (docs/multirate.md
// "lts", "Three domains, the energy in the result files"): run::DomainRecorder writes a row at
// the instants 0, then + interval each (a running sum, with its rounding), and each row carries
// the share of the last coarse instant at or before its instant.
#include <cstdint>

namespace crashlink::daemon {

class HistoryRowInstants {
 public:
  /// interval_s: the history interval [s] (0: a row every cycle); tps: ticks per second;
  /// period: the coarse step of the energy's instants [ticks].
  HistoryRowInstants(double interval_s, std::int64_t tps, std::int64_t period)
      : interval_s_(interval_s), tps_(tps), period_(period) {}

  /// The coarse instant [ticks] whose share the row of instant_s [s] carries: the last at or
  /// before it, the same in every domain (int64 max past the last representable tick). The 1e-6 of
  /// a period takes an instant the recorder's sum left just below a coarse instant as that instant:
  /// far above that sum's rounding, far below any step, and each row comes at or after it in whole
  /// cycles, so its sample is taken.
  std::int64_t coarse_instant(double instant_s) const;

  /// Whether some row reads coarse instant T [ticks]. The rows' instants are replayed as the
  /// recorder sums them. Queries must not go back by more than 2 periods below the largest
  /// T asked so far, which holds for the stepper: it asks about t, t + period, t + 2 period, t
  /// growing.
  bool reads(std::int64_t T);

 private:
  double interval_s_;
  std::int64_t tps_, period_;
  double row_s_ = 0.0;  ///< cursor: a row's instant [s], as the recorder sums it
};

}  // namespace crashlink::daemon
