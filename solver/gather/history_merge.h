#pragma once
// Time-series arithmetic of the gather (gather_results.h): linear interpolation onto another
// domain's sample times and the summed glstat of several domains. Pure functions, no I/O.
//
// Array layouts: `times` [k] ascending; a series of width w is [w k] row-major, sample i at
// w i .. w i + w - 1.
#include <cstddef>
#include <span>
#include <vector>

#include "solver/io/result_writer.h"  // GlstatSample

namespace crashlink::gather {

/// Where t falls among `times`: the value is y[i] + w (y[i+1] - y[i]). w = 0 and exactly y[i]
/// when t equals times[i] (so identical sample times reproduce the data bitwise); clamped to the
/// first or last sample outside [times.front(), times.back()].
struct Bracket {
  std::size_t i = 0;
  double w = 0.0;
};
Bracket bracket(std::span<const double> times, double t);

/// Component `c` of a width-`width` series at the bracket.
double interpolate(std::span<const double> y, std::size_t width, std::size_t c, const Bracket& b);

/// t_end + a relative round-off margin: samples at or before it are "not after t_end".
double end_with_margin(double t_end);

struct GlstatMerge {
  std::vector<io::GlstatSample> rows;
  std::size_t grid = 0;     ///< index of the series whose times were used
  double end_time_s = 0.0;  ///< earliest last time among the non-empty series
};

/// The sum of several domains' glstat series. Empty series are skipped. Grid: the times of the
/// series with the fewest samples (ties: the earliest in `series`), cut at the earliest last time
/// among the series; every series is interpolated there (bracket()). energy_balance_error is
/// recomputed from the summed columns (recompute_balance_error). Empty result if every series is.
GlstatMerge merge_glstat(const std::vector<std::vector<io::GlstatSample>>& series);

/// energy_balance_error of summed rows, as integration::EnergyAccount defines it over the samples:
/// (total - E0 - external) / reference with E0 = total - external of the first row and reference
/// the largest of |kinetic|, |internal|, |E0 + external|, |external| seen so far.
void recompute_balance_error(std::vector<io::GlstatSample>& rows);

/// The reference of recompute_balance_error at the last row: the largest of |kinetic|,
/// |internal|, |E0 + external|, |external| over the rows [J] (0 without rows). The E0 of the
/// summary's percentages (solver/run/energy_summary.h).
double balance_reference_J(const std::vector<io::GlstatSample>& rows);

}  // namespace crashlink::gather
