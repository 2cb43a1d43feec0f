#include "solver/io/disk_space.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <filesystem>
#include <limits>

#include "solver/io/hdf5_handles.h"

namespace crashlink::io {

std::uint64_t writable_bytes(const std::string& file) {
  namespace fs = std::filesystem;
  std::uint64_t left = std::numeric_limits<std::uint64_t>::max();
  std::error_code ec;
  const fs::path dir =
      fs::path(file).parent_path().empty() ? fs::path(".") : fs::path(file).parent_path();
  struct statvfs vfs {};
  // f_blocks = 0: a file system that does not say (some FUSE and network mounts)
  if (::statvfs(dir.c_str(), &vfs) == 0 && vfs.f_blocks > 0)
    left = static_cast<std::uint64_t>(vfs.f_bavail) * static_cast<std::uint64_t>(vfs.f_frsize);
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
    const auto size = fs::is_regular_file(file, ec) ? fs::file_size(file, ec) : 0;
    const auto cap = static_cast<std::uint64_t>(lim.rlim_cur);
    left = std::min(left, cap > size ? cap - size : 0);
  }
  return left;
}

void ensure_space(const std::string& file, const std::string& object, std::uint64_t need_bytes) {
  const std::uint64_t left = writable_bytes(file);
  const std::uint64_t want = 2 * need_bytes + kCloseReserveBytes;
  if (left >= want) return;
  throw ResultFileError(
      file, object,
      fmt::format("the disk is full: {:.2f} MB left for this file, the next write needs about "
                  "{:.2f} MB (and {:.2f} MB kept to close the file readable); the file is closed "
                  "with everything before this write: free space on that file system or write "
                  "elsewhere (--out)",
                  static_cast<double>(left) / 1e6, static_cast<double>(need_bytes) / 1e6,
                  static_cast<double>(kCloseReserveBytes) / 1e6));
}

}  // namespace crashlink::io
