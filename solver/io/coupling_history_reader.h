#pragma once
// Reads one interface's rows back from a coordinator.h5 (io::CouplingHistoryWriter's layout,
// docs/result-format.md): what a restarted coordinator copies from its checkpoint.
#include <string>
#include <vector>

#include "solver/io/coupling_history_writer.h"

namespace crashlink::io {

/// The rows of the group `group_path` ("/coupling/<link>") of `file`, in file order (the common
/// prefix of its columns). Throws ResultFileError when the file or a dataset cannot be read.
std::vector<CouplingSample> read_coupling_rows(const std::string& file,
                                               const std::string& group_path);

}  // namespace crashlink::io
