#pragma once
// The process's peak resident memory, for /timing (the scale benchmark's memory per element).
#include <sys/resource.h>

#include <cstdint>

namespace crashlink::run {

/// Peak resident set size of this process so far, bytes (getrusage's ru_maxrss, in KiB on Linux).
/// In a run over --transport inproc every piece shares the process, and each reports the whole.
inline std::int64_t peak_resident_bytes() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return static_cast<std::int64_t>(u.ru_maxrss) * 1024;
}

}  // namespace crashlink::run
