#pragma once
// Reads /timing back from a result file (docs/result-format.md, DESIGN.md §4): the summary of a
// coupled run is printed from the gathered result.h5 (or, if gathering failed, from the domains'
// own files), whichever processes wrote them.
#include <optional>
#include <string>
#include <vector>

#include "solver/io/result_writer.h"

namespace crashlink::apps {

struct TimingRecord {
  double wall_seconds = 0.0;
  double coordinator_cpu_seconds = 0.0;
  std::vector<io::DomainTiming> domains;  ///< link order
};

/// nullopt when the file cannot be opened or has no /timing; never throws.
std::optional<TimingRecord> read_timing(const std::string& h5_path);

}  // namespace crashlink::apps
