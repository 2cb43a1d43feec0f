#pragma once
// Head Injury Criterion, NHTSA FMVSS 208 (49 CFR 571.208, S6.2): the formula, the search and
// the sign convention are on hic(). Layout: time_s[n] strictly increasing, accel_g[n] (same n).
#include <span>

namespace crashlink::signal {

inline constexpr double kHic15Window_s = 0.015;  ///< FMVSS 208 S6.2 (HIC15)
inline constexpr double kHic36Window_s = 0.036;

struct HicResult {
  double hic = 0.0;   ///< [-] (by convention, a in g and t in s)
  double t1_s = 0.0;  ///< start of the maximising window
  double t2_s = 0.0;  ///< end of the maximising window (t1_s == t2_s when hic == 0)
};

/// HIC, FMVSS 208 (49 CFR 571.208, S6.2):
///   HIC = max over t1 < t2, t2 - t1 <= W of  (t2 - t1) [ 1/(t2 - t1) integral_t1^t2 a dt ]^2.5
/// a = resultant head acceleration in g (g_n = 9.80665 m/s^2), t in seconds; W = max_window_s,
/// 15 ms (HIC15, the current FMVSS 208 criterion) or 36 ms (HIC36, the earlier one).
/// Exact search over the sample instants: every pair (t1, t2) = (t[i], t[j]) with
/// t[j] - t[i] <= W (1 + 1e-9) is evaluated (the slack absorbs round-off of sample instants such
/// as k * 1e-5), the integral taken by the trapezoid rule from a cumulative trapezoid sum so each
/// pair costs O(1) and the search O(n w) (w = samples per window). Non-uniform sampling is allowed.
/// Sign convention: HIC is defined on the resultant magnitude, which is never negative. A 1-D
/// signal (a CSV) is used as given: the caller passes the resultant, or a signed component whose
/// positive sense is the loading direction. A window whose mean acceleration is <= 0 has no real
/// 2.5 power and is skipped (contributes 0); a signal that is never positive has HIC = 0.
/// Throws InputError if the samples are not as stated in the layout (fewer than 2, non-finite,
/// time not increasing) or max_window_s <= 0.
HicResult hic(std::span<const double> time_s, std::span<const double> accel_g, double max_window_s);

/// The same by direct summation of the trapezoids for every pair: O(n * w^2). Reference for tests.
HicResult hic_reference(std::span<const double> time_s, std::span<const double> accel_g,
                        double max_window_s);

}  // namespace crashlink::signal
