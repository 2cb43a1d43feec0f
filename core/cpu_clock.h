#pragma once
// Process and thread CPU time and wall time, in seconds (the run summaries, /timing, advise).
#include <chrono>
#include <ctime>

namespace crashlink::core {

/// CPU seconds consumed by this process (all threads).
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// CPU seconds consumed by the calling thread.
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// A process's CPU seconds, or its thread's when it runs as a thread of a bigger process (crashlink
/// run --transport inproc).
inline double cpu_seconds(bool in_process) {
  return in_process ? thread_cpu_seconds() : process_cpu_seconds();
}

inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace crashlink::core
