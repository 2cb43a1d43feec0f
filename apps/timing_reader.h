#pragma once
// Reads /timing back from a result file (docs/result-format.md, docs/design.md §4): the summary of
// a coupled run is printed from the gathered result.h5 (or, if gathering failed, from the domains'
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
  /// The coordinator's and every domain's CPU [s].
  double total_cpu_seconds() const {
    double sum = coordinator_cpu_seconds;
    for (const auto& d : domains) sum += d.cpu_seconds;
    return sum;
  }
};

/// nullopt when the file cannot be opened or has no /timing; never throws.
std::optional<TimingRecord> read_timing(const std::string& h5_path);

}  // namespace crashlink::apps
