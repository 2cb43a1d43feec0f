#pragma once
// How a coupled run couples its domains: the one configuration that travels from the command line
// (`crashlink run`, `crashlink-coordinator`) through the launcher into the coordinator, which sends
// what the daemons need in each Setup (scheme, mode, variable steps, Options: checkpoint interval,
// drift). It is checked once, by coordinator::validate (coordinator/coordinator_schemes.h), with
// each scheme's own rules in that scheme. The in-process runners (cosim::LayerNetwork,
// cosim::PaperRunner) take the same struct.
#include <cstdint>
#include <string>

#include "coupling/ticks.h"

namespace crashlink::coupling {

/// `lts`: the coarse element layers its cut moves into the finer domain beyond `layer`'s first
/// (partition::decompose). Without one, the plain leapfrog LTS has unstable step bands
/// (coupling-study/lts/README.md; docs/multirate.md "lts").
inline constexpr int kLtsOverlapLayers = 1;

struct CouplingConfig {
  /// The scheme, by name ("layer", "paper"; --coupling).
  std::string scheme = "layer";
  bool common_step = true;  ///< split (true: one common step) or multi (false: each its own)
  /// Each domain's step follows its stable step as the mesh deforms (--variable-steps; `layer`:
  /// multi every domain its own proposal, split all the least; `paper`: each free state's).
  bool variable_steps = false;
  bool drift = true;         ///< `paper`: drift correction [11] (--no-drift: off)
  double guard_rise = 0.05;  ///< `paper`: energy guard (coupling/paper_guard.h)
  /// > 0: a checkpoint at every multiple of this interval, s (docs/design.md §2.6 "Checkpoints").
  double checkpoint_interval_s = 0.0;
  /// Resume from the newest checkpoint the coordinator and every daemon have (--restart).
  bool restart = false;
  /// The daemons exchange their vectors directly when every one offers a lane (--no-lanes: false).
  bool lanes = true;
  std::int64_t ticks_per_second = kDefaultTicksPerSecond;
};

}  // namespace crashlink::coupling
