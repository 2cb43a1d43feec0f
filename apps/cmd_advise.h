#pragma once
// `crashlink advise SCENARIO [--step-safety F]` (issue #5): the element stable steps of every
// part (min, median, max, a histogram on log-spaced bins) and the split into two domains that
// maximises the predicted CPU gain over mono (solver/partition/split_advice.h for the rule), with
// the `domains:` block to paste into the scenario; the scenario's own split is evaluated too.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

namespace crashlink::apps {

struct AdviseOptions {
  std::string scenario;
  double step_safety = 0.9;  ///< as `crashlink run --step-safety`
};

CLI::App* add_advise_command(CLI::App& app, AdviseOptions& options);

/// Prints the advice to `out`; returns 0. Bad input throws InputError.
int run_advise(const AdviseOptions& options, std::FILE* out = stdout);

}  // namespace crashlink::apps
