#pragma once
// The files a coordinator's session makes beside its results (docs/processes.md): the endpoint
// file, the ipc socket ZeroMQ leaves, the shared-memory lane files in /dev/shm, and their removal
// when the run ends or when a killed run left them.
#include <cstdio>
#include <string>
#include <vector>

namespace crashlink::coordinator {

/// Writes `text` to `path` atomically (temporary file in the same folder, then rename). Throws
/// InputError naming the path on failure.
void write_file_atomically(const std::string& path, const std::string& text);

/// Before an ipc run: the shared-memory lane files that killed runs left in /dev/shm (a SIGKILLed
/// launcher takes its pieces with it: nobody removed their 4 MB rings), or, on a machine without
/// /dev/shm, beside the socket (reclaim_lanes_beside_socket); said on `log`.
void reclaim_orphan_lanes(const std::string& bind, std::FILE* log);
/// The lane files beside the ipc socket PATH (where they go without /dev/shm) that no live
/// process holds: PATH.<domain>.bell and PATH.<domain>.from.<partner> only, never the user's
/// PATH.yaml or the like. Returns how many were removed.
std::size_t reclaim_lanes_beside_socket(const std::string& socket_path);

/// After the run: the endpoint file, the ipc socket this coordinator bound (an ipc:// path, no
/// wildcard), and the lanes of the registered daemons (lane_endpoints; a daemon that died leaves
/// its files).
void remove_session_files(const std::string& bind, const std::string& endpoint_file,
                          const std::vector<std::string>& lane_endpoints,
                          const std::vector<std::string>& domains);

}  // namespace crashlink::coordinator
