#pragma once
// Where a coupled run keeps its checkpoints (DESIGN.md §2.6 "Checkpoints", docs/processes.md):
//   OUT/checkpoints/<T>/<who>/   T the instant in ticks (20 digits, so names sort by time),
//                                who = a domain name or "coordinator"
// Each process writes only its own folder: it fills OUT/checkpoints/<T>/.<who>.tmp, then renames
// it to <who> (atomic), so a folder that exists is complete; a process killed while writing
// leaves only a .tmp folder, which the next checkpoint or restart ignores and removes. Each keeps
// its newest `keep` checkpoints. Processes on other hosts each see their own OUT: the coordinator
// learns the daemons' instants from their Register (list_checkpoints) and picks the newest one
// everybody has.
#include <cstdint>
#include <string>
#include <vector>

namespace crashlink::run {

/// OUT/checkpoints/<T>/<who> (whether it exists or not).
std::string checkpoint_folder(const std::string& out, std::int64_t ticks, const std::string& who);
/// The instants with a complete checkpoint of `who`, ascending.
std::vector<std::int64_t> list_checkpoints(const std::string& out, const std::string& who);
/// An empty OUT/checkpoints/<T>/.<who>.tmp to fill; throws CheckpointError if it cannot be made.
std::string begin_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who);
/// Renames the .tmp folder to its final name (replacing an older one of the same instant), syncs
/// the parent folder, and removes checkpoints of `who` older than its newest `keep`.
void commit_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who,
                       std::size_t keep = 3);
/// Removes every checkpoint of `who` (a run that starts from t = 0 in a folder holding some).
void remove_checkpoints(const std::string& out, const std::string& who);
/// Copies a file into a checkpoint folder and syncs it; throws CheckpointError.
void copy_into_checkpoint(const std::string& file, const std::string& folder);

}  // namespace crashlink::run
