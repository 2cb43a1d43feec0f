#pragma once
// The process's peak resident memory, for /timing (the scale benchmark's memory per element).
#include <sys/resource.h>

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace crashlink::run {

/// Peak resident set size of this process so far, bytes: VmHWM of /proc/self/status, the
/// high-water mark of this program's own memory. Not getrusage's ru_maxrss: Linux carries that
/// across exec, so a daemon would report the launcher's peak from before its fork (the model read
/// and cut). ru_maxrss (KiB) where /proc is not mounted. In a run over --transport inproc every
/// piece shares the process, and each reports the whole.
inline std::int64_t peak_resident_bytes() {
  if (std::FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    long long kib = -1;
    while (std::fgets(line, sizeof line, f) != nullptr)
      if (std::strncmp(line, "VmHWM:", 6) == 0 && std::sscanf(line + 6, "%lld", &kib) == 1) break;
    std::fclose(f);
    if (kib >= 0) return static_cast<std::int64_t>(kib) * 1024;
  }
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return static_cast<std::int64_t>(u.ru_maxrss) * 1024;
}

}  // namespace crashlink::run
