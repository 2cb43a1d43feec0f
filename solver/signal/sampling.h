#pragma once
// Sampled time histories: checks of the time base, uniform resampling and resultants.
//
// Array layouts: time_s[n] and values[n] are one sample per row; xyz[3n] is interleaved, sample k
// at 3k..3k+2 (the layout of an [n,3] history dataset of result.h5).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace crashlink::signal {

/// Standard acceleration of gravity g_n [m/s^2] (3rd CGPM 1901; ISO 80000-3): 1 g.
inline constexpr double kStandardGravity_m_s2 = 9.80665;

/// Throws InputError unless time_s has at least `min_samples` finite, strictly increasing values
/// and values.size() == time_s.size() (values finite too). `what` names the signal in messages
/// ("head.csv", "probe head"); the message gives the first offending index and values.
void check_signal(std::span<const double> time_s, std::span<const double> values,
                  const std::string& what, std::size_t min_samples = 2);

/// The sampling of a time base.
struct Sampling {
  double mean_step_s = 0.0;  ///< (t[n-1] - t[0]) / (n - 1)
  double min_step_s = 0.0;
  double max_step_s = 0.0;
  /// (max_step - min_step) / mean_step <= tolerance.
  bool uniform(double relative_tolerance = kUniformTolerance) const {
    return max_step_s - min_step_s <= relative_tolerance * mean_step_s;
  }
  /// Steps may differ by this fraction of the mean and still count as uniform: absorbs time
  /// stamps printed with few digits (a step of 1e-5 s written as 0.0123456 is exact to 1e-7 s).
  static constexpr double kUniformTolerance = 1e-3;
};

/// Mean, min and max step of an increasing time base of at least 2 samples.
Sampling sampling_of(std::span<const double> time_s);

/// Linear interpolation of `values` (sampled at time_s, increasing) at t0 + k*step_s for
/// k = 0 .. floor((t_end - t0)/step_s) with t0 = time_s[0], t_end = time_s[n-1] (the last instant
/// is kept if it is within 1e-9 step of the grid). Returns the new values; *uniform_time_s (if
/// not null) receives the new instants. `components` > 1: values is interleaved [components*n]
/// and so is the result.
std::vector<double> resample_linear(std::span<const double> time_s, std::span<const double> values,
                                    double step_s, std::vector<double>* uniform_time_s = nullptr,
                                    std::size_t components = 1);

/// Magnitude |(x, y, z)| of each sample of interleaved xyz[3n], times `scale` (e.g. 1/g_n to go
/// from m/s^2 to g). Returns [n].
std::vector<double> resultant(std::span<const double> xyz, double scale = 1.0);

}  // namespace crashlink::signal
