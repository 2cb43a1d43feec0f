#pragma once
// The field states of the gather (gather_results.h): /states/<k> of the global model assembled
// from the domain files. State times: those of the domain file with the fewest states, up to the
// earliest last state time; from every other domain the state nearest in time is taken (states
// are snapshots at the same requested instants, field_interval_s, on each domain's own step grid:
// nothing is interpolated). Node fields come from the node's owner (the first domain, in
// decomposition order, where the node is neither a ghost nor a copy and whose file has states);
// element fields of a global part from every domain holding some of its elements, by element id.
// Values no usable file provides: displacement 0 (the mesh stays drawable), velocity and element
// fields NaN; reported in GatherReport::notes.
#include <cstdint>
#include <vector>

#include "solver/gather/domain_files.h"
#include "solver/io/result_writer.h"

namespace crashlink::gather {

/// Writes the gathered states to `writer` (whose model is `global`); returns how many.
std::int64_t write_states(const model::Model& global, const std::vector<DomainFile>& files,
                          io::ResultWriter& writer, GatherReport& report);

}  // namespace crashlink::gather
