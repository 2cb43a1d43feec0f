#pragma once
// `crashlink stability-map [--steps N] [--ratios LIST] [--shapes LIST] [--penalties LIST]
// [--out DIR]` (issue #5): the long-run stability of the couplings across step ratios on the
// study's free-vibration set-up (studies/free_vibration.h: bar, shell plate, hex block;
// `layer` with and without the interface damping, `paper` with drift correction [11] on and off)
// and on a contact across the domains (studies/contact_drop.h: a block dropped on a slab;
// `layer` and `paper` + [11] at each penalty scale); DIR/stability_map.csv (one row per run)
// and DIR/stability_map.png (the maximum energy rise against the ratio, one curve per shape and
// configuration; tools/stability_map.py). The runs are 10^5 fine steps (the default);
// CI checks a short map.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crashlink::apps {

struct StabilityMapOptions {
  long long steps = 100000;
  std::vector<double> ratios{1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 4.7, 6.0, 8.0, 12.0, 16.0};
  std::vector<std::string> shapes{"bar", "plate", "block", "contact"};
  std::vector<double> penalties{0.1, 1.0, 10.0};  ///< contact: penalty scale factors
  std::string out = "out/stability_map";
};

CLI::App* add_stability_map_command(CLI::App& app, StabilityMapOptions& options);

/// Returns 0; 4 when the plotting script failed. Every run is written, stopped ones included.
int run_stability_map(const StabilityMapOptions& options);

}  // namespace crashlink::apps
