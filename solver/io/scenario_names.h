#pragma once
// Names from the scenario that become file or folder names (docs/scenario-format.md "Names that
// become file names"): a domain's name is DIR/domains/<name>.h5 and .xdmf, its checkpoint folder
// DIR/checkpoints/<instant>/<name>/, its shared-memory lane /dev/shm/crashlink-<hash>.<name> and
// its routing id on the wire. (Part, probe and contact names become HDF5 group names, which
// io::result_link_name makes safe; they are not file names.)
//
// The rule: 1 to 64 characters, each an ASCII letter, a digit, '_', '-' or '.', not starting
// with '.', and not "coordinator" (the coordinator's own checkpoint folder). Names of one kind
// must also differ in more than letter case (a case-insensitive file system would merge them).
#include <cstddef>
#include <string>
#include <string_view>

namespace crashlink::io {

inline constexpr std::size_t kMaxFileNameChars = 64;

/// Why `name` cannot be a file name under the rule above, or "" when it can. The text names the
/// offending character and its position (1-based), the rule and, where one exists, a safe name.
std::string file_name_problem(std::string_view name);

/// `name` with every character the rule does not allow replaced by '_' (one per character, also
/// for a multi-byte UTF-8 one), leading dots dropped, cut to the length limit: a suggestion.
std::string safe_file_name(std::string_view name);

}  // namespace crashlink::io
