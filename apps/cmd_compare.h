#pragma once
// `crashlink compare REFERENCE.h5 RUN.h5 [REFERENCE.h5 RUN.h5 ...] [--probe NAME]`: the paper's
// Table 1 (Bourel, Combescure & Di Valentin 2005, §4.2) for two runs of one scene, typically
// `mono` against `multi`: elements, critical step, cycles and CPU per domain, the coordinator's
// CPU, the total, the CPU gain against the ideal one, the wall-clock gain, and the head metrics
// (HIC15, HIC36, peak resultant acceleration after CFC 1000) with their differences.
// Several pairs (repeated runs of the same scene): each pair's table, then one line per pair and
// the medians (CPU times vary by ±10 % from run to run on a shared machine; quote medians).
//
// Ideal gain (from element counts and steps, as the paper's 2.31):
//   (N_ref / dt_ref) / sum_k (N_k / dt_k)
// i.e. element-cycles per simulated second of the reference over those of the run, assuming every
// element costs the same per cycle.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

namespace crashlink::apps {

struct CompareOptions {
  std::string reference;  ///< result.h5 of the reference run (mono)
  std::string run;        ///< result.h5 of the run compared with it (split / multi)
  std::string probe;      ///< head probe; "" = the first rigid-body probe of the reference
  /// The command line's files: reference, run, reference, run, ... (run_compare).
  std::vector<std::string> files;
};

/// What the table shows, for tests and for `crashlink run --reference`.
struct Comparison {
  double cpu_reference_s = 0.0, cpu_run_s = 0.0, coordinator_cpu_s = 0.0;
  double wall_reference_s = 0.0, wall_run_s = 0.0;
  double gain = 0.0, ideal_gain = 0.0, wall_gain = 0.0;
  double coordinator_share = 0.0;  ///< of the run's total CPU
  double hic15_reference = 0.0, hic15_run = 0.0, hic15_difference = 0.0;  ///< relative
  double peak_g_reference = 0.0, peak_g_run = 0.0;
  bool has_head = false;
};

CLI::App* add_compare_command(CLI::App& app, CompareOptions& options);

/// Prints the table to `out` and returns what it shows. Throws InputError if a file has no
/// /timing (not a finished run) or the probe is missing; io::ResultFileError if unreadable.
Comparison compare_runs(const CompareOptions& options, std::FILE* out = stdout);

/// The medians of several comparisons (the mean of the middle two for an even count) and one
/// line per pair, printed to `out`; returns the medians (has_head: every pair had one).
Comparison print_medians(const std::vector<Comparison>& pairs, std::FILE* out = stdout);

/// `crashlink compare`: every pair of `files`, then the medians when there are several.
/// Throws InputError for an odd count of files.
int run_compare(const CompareOptions& options);

}  // namespace crashlink::apps
