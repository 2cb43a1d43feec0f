#pragma once
// Where a coupled run keeps its checkpoints (docs/checkpoints.md "When"):
//   OUT/checkpoints/<T>/<who>/   T the instant in ticks (20 digits, so names sort by time),
//                                who = a domain name or "coordinator" (a "piece")
// Each process writes only its own folder: it fills OUT/checkpoints/<T>/.<who>.tmp, writes a
// MANIFEST (size and FNV-1a 64 of every file), then renames it to <who> (atomic), so a folder that
// exists is complete and a damaged file is found by its manifest. An instant is complete when
// every piece of the run has it; a piece removes its checkpoints older than the newest `keep`
// complete instants only, so a restart always finds a complete instant however far one piece
// runs ahead of another. Processes on other hosts each see their own OUT: the coordinator learns
// the daemons' instants from their Register (list_sound_checkpoints) and picks the newest one
// everybody has intact; a piece that cannot see the others' folders prunes nothing.
#include <cstdint>
#include <string>
#include <vector>

namespace crashlink::run {

/// The coordinator's piece, beside the domains' (it keeps one only for a cut with an interface).
inline constexpr const char* kCoordinatorPiece = "coordinator";
/// The pieces of a run's checkpoints: every domain, and the coordinator if `with_coordinator`.
std::vector<std::string> checkpoint_pieces(std::vector<std::string> domains, bool with_coordinator);

/// OUT/checkpoints/<T>/<who> (whether it exists or not).
std::string checkpoint_folder(const std::string& out, std::int64_t ticks, const std::string& who);
/// The instants with a complete (renamed) checkpoint of `who`, ascending; files not checked.
std::vector<std::int64_t> list_checkpoints(const std::string& out, const std::string& who);
/// The pieces with a complete checkpoint at some instant in OUT, sorted (what a restart is offered:
/// a mono run's domain, or a coupled run's domains and coordinator).
std::vector<std::string> checkpoint_owners(const std::string& out);
/// Those of list_checkpoints whose files all match their MANIFEST, ascending. Each damaged one
/// adds "FOLDER: reason" to `damaged` (if given).
std::vector<std::int64_t> list_sound_checkpoints(const std::string& out, const std::string& who,
                                                 std::vector<std::string>* damaged = nullptr);
/// "" if every file that the folder's MANIFEST lists has its size and hash, else the reason
/// (no manifest, a file missing, shorter or longer, its hash).
std::string verify_checkpoint(const std::string& folder);
/// The instants at which every piece in `pieces` has a complete checkpoint, ascending.
std::vector<std::int64_t> complete_instants(const std::string& out,
                                            const std::vector<std::string>& pieces);
/// An empty OUT/checkpoints/<T>/.<who>.tmp to fill; throws CheckpointError if it cannot be made.
std::string begin_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who);
/// Writes the .tmp folder's MANIFEST, renames it to its final name (replacing an older one of the
/// same instant), syncs the parent folder, then prune_checkpoints(out, pieces, {who}, keep).
void commit_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who,
                       const std::vector<std::string>& pieces, std::size_t keep = 3);
/// Removes the checkpoints of each of `whose` at instants older than the keep-th newest complete
/// instant of `pieces` (nothing while fewer than `keep` are complete).
void prune_checkpoints(const std::string& out, const std::vector<std::string>& pieces,
                       const std::vector<std::string>& whose, std::size_t keep = 3);
/// Removes every checkpoint of `who` (a run that starts from t = 0 in a folder holding some).
void remove_checkpoints(const std::string& out, const std::string& who);
/// Copies a file into a checkpoint folder and syncs it; throws CheckpointError.
void copy_into_checkpoint(const std::string& file, const std::string& folder);

}  // namespace crashlink::run
