#pragma once
// Restart of a run from a checkpoint (docs/design.md §2.6 "Checkpoints"): the result file a
// restarted domain writes starts with what the interrupted run had written before the checkpoint.
// The checkpoint keeps a copy of the domain's result file taken at the checkpoint instant; this
// copies its rows and field states into the new file, so the new file ends up holding the whole
// run.
#include <cstddef>
#include <string>

#include "solver/io/result_writer.h"

namespace crashlink::io {

struct ReplayCounts {
  std::size_t glstat_rows = 0;
  std::size_t probe_rows = 0;  ///< summed over the probes
  std::size_t contact_rows = 0;
  std::size_t states = 0;
};

/// Appends to `to` (a new writer for `model`, nothing written yet) every glstat, probe and contact
/// row and every field state of the result file `from` whose time is < before_s. Throws
/// ResultFileError / InputError when `from` cannot be read or does not hold this model's probes,
/// contacts and parts.
ReplayCounts replay_results(const std::string& from, ResultWriter& to, const model::Model& model,
                            double before_s);

}  // namespace crashlink::io
