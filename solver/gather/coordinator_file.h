#pragma once
// The coordinator's side of the gather (gather_results.h): DIR/coordinator.h5, written by
// io::CouplingHistoryWriter (docs/result-format.md, "coordinator.h5"), is read for its /timing
// and its /coupling group is copied into the gathered result.h5.
#include <map>
#include <string>

#include "solver/gather/gather_results.h"

namespace crashlink::gather {

struct CoordinatorTiming {
  bool present = false;  ///< coordinator.h5 was read
  double wall_seconds = 0.0;
  double coordinator_cpu_seconds = 0.0;
  std::map<std::string, double> wait_seconds;  ///< by /timing/<link> group name
};

/// Reads DIR/coordinator.h5's /timing; absent or unreadable: present = false and a note.
CoordinatorTiming read_coordinator_timing(const std::string& dir, GatherReport& report);

/// Finishes the closed result file `result_h5`: copies /coupling from DIR/coordinator.h5 (if
/// present), adds the attribute wait_seconds to /timing/<link> for every entry of `timing` (the
/// group created with attribute name = `names[link]` if needed) and writes the root attribute
/// gather_notes (the report's notes, one per line) if there are any. Failures to copy are noted,
/// not thrown; a result file that cannot be opened throws io::ResultFileError.
void finish_result_file(const std::string& result_h5, const std::string& dir,
                        const CoordinatorTiming& timing,
                        const std::map<std::string, std::string>& names, GatherReport& report);

}  // namespace crashlink::gather
