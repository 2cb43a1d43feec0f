#include "coordinator/session_files.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "transport/shm_lane.h"

namespace crashlink::coordinator {

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = fmt::format("{}.tmp{}", path, static_cast<long>(::getpid()));
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw InputError(fmt::format("cannot write {}", tmp));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(fmt::format("cannot rename {} to {}: {}", tmp, path, ec.message()));
}

std::size_t reclaim_lanes_beside_socket(const std::string& socket_path) {
  const std::filesystem::path socket(socket_path);
  const auto dir = socket.parent_path().empty() ? std::filesystem::path(".") : socket.parent_path();
  return transport::reclaim_orphan_shm_files(dir.string(), socket.filename().string() + ".", true);
}

void reclaim_orphan_lanes(const std::string& bind, std::FILE* log) {
  if (bind.rfind("ipc://", 0) != 0) return;
  std::size_t n = transport::reclaim_orphan_shm_files("/dev/shm", "crashlink-");
  // Without /dev/shm the rings sit beside the socket (lane_endpoint.h): a run killed there and
  // restarted in the same folder would otherwise leave a partner, which opens its rings at once,
  // a stale file to map before the receiver has replaced it.
  std::error_code ec;
  if (!std::filesystem::is_directory("/dev/shm", ec) && bind.find('*') == std::string::npos)
    n += reclaim_lanes_beside_socket(bind.substr(6));
  if (n > 0 && log != nullptr) {
    std::fprintf(log,
                 "crashlink-coordinator: removed %zu shared-memory lane file(s) left by runs "
                 "that were killed\n",
                 n);
    std::fflush(log);
  }
}

void remove_session_files(const std::string& bind, const std::string& endpoint_file,
                          const std::vector<std::string>& lane_endpoints,
                          const std::vector<std::string>& domains) {
  for (const auto& lane : lane_endpoints) transport::remove_shm_lane_files(lane, domains);
  std::error_code ec;
  if (!endpoint_file.empty()) std::filesystem::remove(endpoint_file, ec);
  const std::string ipc = "ipc://";
  if (bind.rfind(ipc, 0) == 0 && bind.find('*') == std::string::npos) {
    const std::string path = bind.substr(ipc.size());
    if (std::filesystem::is_socket(path, ec)) std::filesystem::remove(path, ec);
  }
}

}  // namespace crashlink::coordinator
