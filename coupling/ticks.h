#pragma once
// Time as an integer count of ticks (docs/design.md §2.6: "never compare doubles for equality to
// decide who waits"). Every time and step on the wire and in the scheduler is a Tick. The tick
// length rule: TickClock; rounding seconds to ticks: TickClock::to_ticks.
#include <cstdint>

namespace crashlink::coupling {

using Tick = std::int64_t;

inline constexpr std::int64_t kDefaultTicksPerSecond = 1'000'000'000'000'000;  // 1 tick = 1 fs

/// Tick length rule:
/// - One tick is 1 / ticks_per_second seconds, ticks_per_second an integer; the default is 10^15
///   (1 fs). A decimal tick makes the steps people write (1e-6 s, 2.5e-7 s) whole numbers of
///   ticks, so steps in ratio 1:3 or 1:1.5 give instants that coincide exactly and [10] of Bourel
///   2005 is not needed there. An int64 of femtoseconds spans 9223 s; to_seconds is exact to the
///   last bit up to 2^53 ticks (9 s).
/// - Not chosen: "the greatest tick that divides every domain's step": stable steps change every
///   cycle ([1], [2] with variable steps), so no such tick exists for a real run.
/// - With 1 fs, a 1e-8 s step loses at most 1e-7 of itself to rounding (to_ticks).
class TickClock {
 public:
  /// Values within this many ulps of a whole number of ticks snap to it (to_ticks).
  static constexpr double kSnapUlps = 4.0;

  /// Throws crashlink::ModelError unless 1 <= ticks_per_second <= 2^53 (exact in a double).
  explicit TickClock(std::int64_t ticks_per_second = kDefaultTicksPerSecond);

  std::int64_t ticks_per_second() const { return ticks_per_second_; }
  /// Tick length, s (rounded; only for display).
  double tick_s() const { return 1.0 / static_cast<double>(ticks_per_second_); }

  /// n ticks in seconds: the double nearest to n / ticks_per_second (exact rounding for
  /// |n| <= 2^53).
  double to_seconds(Tick n) const;

  /// An instant or duration t >= 0 in seconds to ticks: the greatest n with n ticks <= t, after
  /// snapping. Steps are rounded DOWN to whole ticks, so a step never exceeds the stable step it
  /// came from. One exception, by design: a value that is a whole number of ticks up to the
  /// rounding of the double it arrived in (within kSnapUlps ulps, about 1e-15 relative) is taken
  /// as that whole number, so 3e-6 s is 3'000'000'000 ticks and not 2'999'999'999. That excess is
  /// below the precision of any stable-step estimate (Courant safety factors are ~0.9).
  /// Throws crashlink::NumericalError for a negative or non-finite t (a blown-up step)
  /// and crashlink::ModelError when t does not fit in 2^62 ticks.
  Tick to_ticks(double t_s) const;

  /// A step dt > 0 in seconds to ticks, rounded down (to_ticks). Throws crashlink::ModelError when
  /// the step is shorter than one tick (the fix: a larger ticks_per_second).
  Tick step_to_ticks(double dt_s) const;

 private:
  std::int64_t ticks_per_second_;
};

}  // namespace crashlink::coupling
