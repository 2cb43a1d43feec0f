#pragma once
// Head-impact metrics of a headform's 3-axis acceleration history, the way a test lab computes
// them (SAE J211/1, FMVSS 208 S6.2): each channel resampled to a uniform step if needed, filtered
// by its CFC, the resultant taken in g, then peak and HIC15 / HIC36 (solver/signal/hic.h).
// One implementation for `crashlink hic`, `crashlink compare`, `crashlink sweep` and the report.
//
// Layout: time_s[n] increasing; channels: three (x, y, z: the resultant is used) or one (used as
// given, signed: a CSV's resultant or loading-direction component), each [n].
#include <span>
#include <string>
#include <vector>

#include "solver/signal/hic.h"

namespace crashlink::signal {

struct HeadMetrics {
  std::vector<double> time_s;   ///< [m] uniform (resampled) time base of the filtered series
  std::vector<double> accel_g;  ///< [m] filtered resultant, g
  bool resampled = false;       ///< the input was not uniform and was resampled to its mean step
  double min_step_s = 0.0, max_step_s = 0.0, mean_step_s = 0.0;  ///< of the input time base
  int cfc = 0;                                                   ///< 0: not filtered
  double peak_g = 0.0;
  double peak_time_s = 0.0;
  HicResult hic15;
  HicResult hic36;
};

/// cfc: 1000, 600, 180, 60 or 0 (no filter); to_g converts the channels' unit to g (1/g_n for
/// m/s^2). Throws InputError on a bad time base, channel count or class; `what` names the signal.
HeadMetrics head_metrics(std::span<const double> time_s, std::vector<std::vector<double>> channels,
                         double to_g, int cfc, const std::string& what);

/// The common case: a result probe's [3n] interleaved acceleration in m/s^2.
HeadMetrics head_metrics_xyz(std::span<const double> time_s, std::span<const double> accel_xyz_m_s2,
                             int cfc, const std::string& what);

}  // namespace crashlink::signal
