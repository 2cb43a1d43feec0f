#pragma once
// Room left for a result file, checked before each write so that a filling disk stops the run
// with a closed, readable file instead of an HDF5 file whose metadata points past its end.
#include <cstdint>
#include <string>

namespace crashlink::io {

/// Bytes that can still be added to `file` (existing or not): the least of the file system's free
/// bytes (statvfs f_bavail x f_frsize, what an unprivileged process may use) and the process's
/// file-size limit (RLIMIT_FSIZE) less the file's size.
std::uint64_t writable_bytes(const std::string& file);

/// What a result file keeps free besides the next write: HDF5's chunk allocations and the metadata
/// that closing the file writes (a few hundred kB for the head-impact scene).
inline constexpr std::uint64_t kCloseReserveBytes = std::uint64_t{1} << 20;

/// Throws ResultFileError at `object` when fewer than 2 x need_bytes + kCloseReserveBytes remain
/// (the factor 2 covers chunk rounding and HDF5's copies), naming both sizes and the fix.
void ensure_space(const std::string& file, const std::string& object, std::uint64_t need_bytes);

}  // namespace crashlink::io
