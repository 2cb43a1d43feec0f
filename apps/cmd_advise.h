#pragma once
// `crashlink advise SCENARIO [--step-safety F] [--domains N]` (issue #5): the element stable steps
// of every part (min, median, max, a histogram on log-spaced bins) and the split into two (or N)
// domains that maximises the predicted CPU gain over mono (solver/partition/split_advice.h for the
// rule), with the `domains:` block to paste into the scenario; the scenario's own split is
// evaluated too.
// --process-sample F: the scenario's own split also timed over processes (advise_process_sample.h),
// which counts what the messages and the coordinator cost. A keyword deck (`crashlink advise
// model.k [--units U]`): the same advice, and the scenario to write around the deck (its `model:`
// line and `domains:` by part title or PID).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/shared_defaults.h"

namespace crashlink::apps {

struct AdviseOptions {
  std::string scenario;
  double step_safety = SharedDefaults::step_safety;  ///< as `crashlink run --step-safety`
  /// > 0: also the scenario's own split timed on processes over [F, 2F] of the end time
  /// (advise_process_sample.h).
  double process_sample = 0.0;
  /// The number of domains of the cuts proposed (2: the two-domain splits; N > 2: consecutive
  /// groups of parts by step, nested steps).
  int domains = 2;
  /// A keyword deck's unit system and keywords to skip (as `crashlink run`); empty: inferred.
  std::string units;
  std::vector<std::string> ignore;
};

CLI::App* add_advise_command(CLI::App& app, AdviseOptions& options);

/// Prints the advice to `out`; returns 0. Bad input throws InputError.
int run_advise(const AdviseOptions& options, std::FILE* out = stdout);

}  // namespace crashlink::apps
