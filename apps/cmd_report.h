#pragma once
// `crashlink report RESULT.h5 [--out DIR] [--probe NAME]`: the PNGs an engineer looks at first:
// head acceleration (g) against time (ms) after CFC 1000 with the HIC15 window shaded and its
// value; the energy balance with each contact interface's energy; the interface drift
// (/coupling); the contact forces after CFC 180.
// The head metrics are computed here (solver/signal/head_metrics.h, the one filter and HIC
// implementation) and written to DIR/head_cfc1000.csv, the filtered contact forces to
// DIR/contact_forces_cfc180.csv (contact_force_csv.h); the plots are drawn by tools/report.py
// (/usr/bin/python3 with python3-matplotlib and python3-h5py). DIR defaults to RESULT's folder
// + /report. Prints the path of every file written.
#include <CLI/CLI.hpp>
#include <string>

namespace crashlink::apps {

struct ReportOptions {
  std::string result;
  std::string out;    ///< "" = <folder of result>/report
  std::string probe;  ///< "" = the first rigid-body probe (none: no head plot)
};

CLI::App* add_report_command(CLI::App& app, ReportOptions& options);

/// Returns 0, or 4 when the plotting script failed (its message is on stderr). Bad input throws
/// InputError.
int run_report(const ReportOptions& options);

}  // namespace crashlink::apps
