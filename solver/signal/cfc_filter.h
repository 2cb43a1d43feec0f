#pragma once
// SAE J211/1 (Instrumentation for Impact Test, Part 1: Electronic Instrumentation), Appendix C,
// and ISO 6487: channel frequency class (CFC) filter. The 4-pole phaseless Butterworth low-pass
// is a 2-pole Butterworth run forward, then backward over the result (zero phase: the backward
// pass cancels the phase of the forward one; magnitude = |H2|^2). Uniform sampling is required
// (the coefficients depend on the sample period T). The coefficients are on cfc_coefficients,
// the pass on cfc_pass, the treatment of the record's ends on cfc_filter.
#include <span>
#include <string>
#include <vector>

namespace crashlink::signal {

/// The channel frequency classes J211/1 recommends: 60, 180, 600, 1000.
bool is_cfc_class(int cfc);

/// J211/1 Appendix C coefficients of the 2-pole pass (Y[t] = a0 X[t] + ... + b2 Y[t-2]).
struct CfcCoefficients {
  double a0 = 0.0, a1 = 0.0, a2 = 0.0, b1 = 0.0, b2 = 0.0;
};

/// 2-pole coefficients, J211/1 Appendix C (T = sample_period_s [s]):
///   wd = 2 pi CFC 2.0775               (2-pole corner: CFC 1000 -> 2077.5 Hz; the double pass
///                                       is -3 dB near F_N = 1.65 CFC)
///   wa = sin(wd T/2) / cos(wd T/2)     (bilinear prewarping)
///   a0 = wa^2 / (1 + sqrt2 wa + wa^2),  a1 = 2 a0,  a2 = a0
///   b1 = -2 (wa^2 - 1) / (1 + sqrt2 wa + wa^2)
///   b2 = (-1 + sqrt2 wa - wa^2) / (1 + sqrt2 wa + wa^2)
/// Throws InputError if cfc is not one of 60, 180, 600, 1000, or the sample period is not
/// positive or too long for the class (wd T/2 >= 0.49 pi, i.e. a sample rate below
/// about 4.24 CFC, where the prewarped corner runs into the Nyquist frequency).
CfcCoefficients cfc_coefficients(int cfc, double sample_period_s);

/// Gain |H(f)| of the whole filter (both passes) at frequency f [Hz]: |H2(e^{i 2 pi f T})|^2.
double cfc_gain(int cfc, double sample_period_s, double frequency_Hz);

/// Filters x[n], one value per sample, sampled every sample_period_s T (uniform): forward, then
/// backward with cfc_pass. Returns [n]. Filter each channel of a 3-D probe separately, then form
/// the resultant, as J211/1 does for resultants of filtered channels.
/// Start-up (the ends of the record): J211/1 asks for data beyond the interval of interest so
/// that the filter's start-up does not reach it; here each end is extended by an odd reflection
/// about the end sample (x[-k] = 2 x[0] - x[k], which keeps the end value and slope: a constant or
/// a ramp passes unchanged), of length min(n - 1, ceil(4 / (2.0775 CFC T))) samples, i.e. four
/// periods of the 2-pole corner (the start-up transient decays by ~1e-8 over it). The padding is
/// dropped after the backward pass. This is the "odd" padding of MATLAB's / SciPy's filtfilt.
std::vector<double> cfc_filter(std::span<const double> x, double sample_period_s, int cfc);

/// The same for samples at time_s[n]: throws InputError unless the sampling is uniform within
/// Sampling::kUniformTolerance (message: the step range and the fix); T = mean step.
std::vector<double> cfc_filter(std::span<const double> time_s, std::span<const double> x, int cfc,
                               const std::string& what = "signal");

/// One 2-pole pass only (phase-shifting), forward over x from its first sample (J211/1
/// Appendix C):
///   Y[t] = a0 X[t] + a1 X[t-1] + a2 X[t-2] + b1 Y[t-1] + b2 Y[t-2],
/// starting at rest on its first input (Y[0] = X[0], Y[1] = X[1]). For cfc_filter, for tests and
/// for users who need J211/1's 2-pole response.
std::vector<double> cfc_pass(std::span<const double> x, const CfcCoefficients& k);

}  // namespace crashlink::signal
