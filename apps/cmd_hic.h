#pragma once
// `crashlink hic FILE [--probe NAME] [--cfc 1000|600|180|60|none] [--window 15|36]
//  [--csv-out F]`
// (docs/design.md §4): HIC15 and HIC36 (solver/signal/hic.h) of a head acceleration history,
// after the SAE J211/1 CFC filter (solver/signal/cfc_filter.h). Input and output: run_hic.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

namespace crashlink::apps {

struct HicOptions {
  std::string file;
  std::string probe;    ///< result.h5 only
  std::string cfc;      ///< "1000", "600", "180", "60", "none"; "" = default for the file kind
  int window_ms = 0;    ///< 15 or 36; 0 = both
  std::string csv_out;  ///< if set: the filtered resultant written as time_ms,accel_g
};

/// Adds the `hic` subcommand to `app`, parsing into `options` (which must outlive the parse).
CLI::App* add_hic_command(CLI::App& app, HicOptions& options);

/// Runs the command, printing to `out`. FILE is a CSV `time_s,accel_g`
/// (solver/signal/signal_csv.h; the 1-D value is used as given) or a result.h5 with --probe NAME
/// (/history/probes/NAME/{time, acceleration}: each of the three components is filtered, then the
/// resultant magnitude is converted from m/s^2 to g). Filter: default CFC 1000 for results, none
/// for CSV. The filter needs uniform sampling; a non-uniform history (solver output is sampled at
/// the first cycle after each history instant) is first resampled linearly to its mean step, and
/// the command says so. Output:
///   crashlink hic: FILE[, probe 'NAME' (kind)]: N samples, t0 - tend ms
///   sampling: ...
///   filter: CFC 1000 (SAE J211/1 4-pole phaseless Butterworth) | filter: none
///   peak resultant acceleration = <g> g at <ms> ms     ("peak acceleration" for a CSV)
///   HIC15 = <value> (t1 = <ms> ms, t2 = <ms> ms)
///   HIC36 = <value> (t1 = <ms> ms, t2 = <ms> ms)
/// Returns the exit code (0). Bad input throws crashlink::InputError (exit 2 in
/// crashlink_main.cpp) with the fix; an unreadable result file throws io::ResultFileError.
int run_hic(const HicOptions& options, std::FILE* out = stdout);

}  // namespace crashlink::apps
