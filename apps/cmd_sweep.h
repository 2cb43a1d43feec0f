#pragma once
// `crashlink sweep SCENARIO [--out DIR] [--disp-probe NAME] [--refine PART=N1,N2,...]`: the
// speed-accuracy chart of one scene, DIR/sweep.csv and DIR/sweep.png (tools/sweep_chart.py).
// The configurations and the table: run_sweep; the head-impact scene's sweep:
// docs/head-impact.md "Commands".
#include <CLI/CLI.hpp>
#include <string>

namespace crashlink::apps {

struct SweepOptions {
  std::string scenario;
  std::string out = "out/sweep";
  std::string disp_probe;  ///< "" = the first node probe
  /// "PART=N1,N2,...": also the scene refined to `divisions: N` of PART's mesh (mono and multi).
  std::string refine;
};

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);

/// Runs, each into DIR/<configuration>/:
///   mono         the reference (global minimum step);
///   split        `layer`, every domain at the common step (processes);
///   multi        `layer`, each domain at its own step (processes);
///   lts          `lts` (issue 25), each domain at its own step (processes);
///   paper, paper_no_drift  the seed's scheme with drift correction [11] on and off, in this
///                process at multi's ratio (apps/sweep_paper.h);
///   mass_scaled  mono with conventional mass scaling of the fine domain's parts: each part whose
///                smallest element step is below the coarse domains' is given the density that
///                brings it there (its mass grows by the square of the step ratio; the added mass
///                is in the table): what users pick today instead of multi-time-step.
/// Then DIR/sweep.csv (configuration, CPU and its ratio to mono, wall, HIC15, peak acceleration
/// after CFC 1000, the displacement probe's peak, each with its error against mono, added mass)
/// and DIR/sweep.png (x: CPU relative to mono; y: error against mono, one marker per quantity;
/// tools/sweep_chart.py).
/// --refine PART=N1,N2,... adds, per N, the scene with the generated mesh of PART given
/// `divisions: N` (its length divisions: the fine part's elements shorter, the step ratio larger),
/// run mono_N and multi_N; multi_N's CPU and errors are against mono_N (the same mesh), and the
/// CSV's step_ratio column says how far apart the domains' steps are.
/// A configuration the solver's guard stops (`paper` going unstable, mass scaling blowing up) is a
/// row saying when and why, and named under the chart: the configuration's result, not a failure
/// of the sweep (exit 0). A reference run that fails, or a file that cannot be written, is one.
/// Returns 0; the exit code of the first run that failed otherwise (the others still run).
int run_sweep(const SweepOptions& options);

}  // namespace crashlink::apps
