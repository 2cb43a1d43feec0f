#pragma once
// A test channel treated as a lab treats it (SAE J211/1): the time base checked, every channel
// resampled to the mean step if the sampling is not uniform (the filter needs a uniform step),
// then filtered by its channel frequency class (cfc_filter.h). One implementation for the
// headform (head_metrics.h: CFC 1000) and the contact forces of the report (CFC 180, the class
// J211/1 recommends for structural forces and loads).
//
// Layout: time_s[n] increasing; channels: each [n] (x, y, z of a 3-axis signal, or one).
#include <span>
#include <string>
#include <vector>

#include "solver/signal/sampling.h"

namespace crashlink::signal {

/// The channel frequency class for structural forces (SAE J211/1 Appendix A: "structural
/// loads", "belt forces" and similar: CFC 180), used for the report's contact forces.
inline constexpr int kStructuralForceCfc = 180;

struct FilteredChannels {
  std::vector<double> time_s;                 ///< [m] the (resampled) time base of the result
  std::vector<std::vector<double>> channels;  ///< each [m], filtered
  bool resampled = false;  ///< the input was not uniform and was resampled to its mean step
  Sampling input;          ///< of the input time base
  int cfc = 0;             ///< 0: not filtered
};

/// Checks every channel against time_s (at least 2 finite samples, increasing times), then
/// resamples (when cfc != 0 and the sampling is not uniform) and filters each channel by CFC
/// `cfc` (60, 180, 600, 1000; 0: none). Throws InputError naming `what` on a bad time base or
/// class, or a sample rate too low for the class.
FilteredChannels filter_channels(std::span<const double> time_s,
                                 std::vector<std::vector<double>> channels, int cfc,
                                 const std::string& what);

/// The x, y, z channels of interleaved xyz[3n] (a [n,3] history dataset), each [n].
std::vector<std::vector<double>> xyz_channels(std::span<const double> xyz);

/// |(x, y, z)| of three channels of equal length, times `scale`. Returns [n].
std::vector<double> channel_resultant(const std::vector<std::vector<double>>& xyz,
                                      double scale = 1.0);

}  // namespace crashlink::signal
