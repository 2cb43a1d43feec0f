// What a daemon pays, in CPU time, each time it sleeps on its lane and is woken
// (docs/head-impact.md "Where the CPU goes"). Two processes hand a turn back and forth, as two
// coupled daemons do once per coarse step: each does W us of busy work, passes the turn
// (transport::ShmDoorbell::ring, the lane's futex wake-up) and waits for it to come back, polling
// for --spin-us and then sleeping on its doorbell (ShmDoorbell::sleep, the lane's futex wait). Each
// process reports its CPU time per turn (getrusage: user + system) minus W: the cost of one sleep
// and one wake-up, which a run's CPU time carries and the element counts do not.
//
//   bench_wake [--turns 20000] [--work-us 300] [--spin-us 0] [--one-core]
//
// --one-core pins both processes to CPU 0 (the paper's single-processor setting): the turn passes
// by a context switch instead of waking an idle core. Prints one line per process and exits 0;
// 2 on bad arguments or a failed child.
#include <fmt/format.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "transport/shm_queue.h"

namespace {

using crashlink::transport::ShmDoorbell;
using Clock = std::chrono::steady_clock;

struct Options {
  long turns = 20000;
  double work_us = 300.0;
  double spin_us = 0.0;
  bool one_core = false;
};

double cpu_seconds() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

volatile double g_sink = 0.0;

void busy(double us) {  // arithmetic, not a sleep: the CPU the work itself takes
  const auto t0 = Clock::now();
  double x = 1.0;
  while (micros_since(t0) < us)
    for (int i = 0; i < 64; ++i) x = x * 1.0000001 + 1e-9;
  g_sink = x;
}

/// Player `me` (0 or 1): the turn is the player's when turn % 2 == me.
int play(int me, const Options& o, std::atomic<std::uint64_t>& turn, ShmDoorbell& mine,
         ShmDoorbell& theirs) {
  long sleeps = 0;
  const double c0 = cpu_seconds();
  const auto t0 = Clock::now();
  for (long k = 0; k < o.turns; ++k) {
    for (;;) {  // wait for the turn: poll, then sleep on the doorbell (ShmLaneIn::receive's way)
      const std::uint32_t seen = mine.count();
      if (turn.load() % 2 == static_cast<std::uint64_t>(me)) break;
      const auto ts = Clock::now();
      bool got = false;
      while (micros_since(ts) < o.spin_us)
        if (turn.load() % 2 == static_cast<std::uint64_t>(me)) {
          got = true;
          break;
        }
      if (got) break;
      ++sleeps;
      mine.sleep(seen, std::chrono::microseconds{1000000});
    }
    busy(o.work_us);
    turn.fetch_add(1);
    theirs.ring();
  }
  const double cpu_us = 1e6 * (cpu_seconds() - c0) / static_cast<double>(o.turns);
  const double wall_us = micros_since(t0) / static_cast<double>(o.turns);
  std::printf(
      "process %d: work %.0f us/turn, CPU %.1f us/turn: %.1f us over the work; %.2f sleeps/turn; "
      "wall %.1f us/turn\n",
      me, o.work_us, cpu_us, cpu_us - o.work_us,
      static_cast<double>(sleeps) / static_cast<double>(o.turns), wall_us);
  std::fflush(stdout);
  return 0;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--turns" && has_value)
      o.turns = std::strtol(argv[++i], nullptr, 10);
    else if (a == "--work-us" && has_value)
      o.work_us = std::strtod(argv[++i], nullptr);
    else if (a == "--spin-us" && has_value)
      o.spin_us = std::strtod(argv[++i], nullptr);
    else if (a == "--one-core")
      o.one_core = true;
    else
      return false;
  }
  return o.turns > 0 && o.work_us >= 0.0 && o.spin_us >= 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::fprintf(stderr,
                 "usage: bench_wake [--turns N > 0] [--work-us W >= 0] [--spin-us S >= 0] "
                 "[--one-core]\n");
    return 2;
  }
  const std::string base = fmt::format("/dev/shm/crashlink-bench-wake-{}", ::getpid());
  // the turn: anonymous shared memory, inherited by the two children
  void* shared = ::mmap(nullptr, 4096, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) {
    std::fprintf(stderr, "bench_wake: mmap failed: %s\n", std::strerror(errno));
    return 2;
  }
  auto* turn = new (shared) std::atomic<std::uint64_t>(0);
  ShmDoorbell bells[2] = {ShmDoorbell::create(base + ".0.bell"),
                          ShmDoorbell::create(base + ".1.bell")};
  if (o.one_core) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(0, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) {
      std::fprintf(stderr, "bench_wake: cannot pin to CPU 0: %s\n", std::strerror(errno));
      return 2;
    }
  }
  std::printf("bench_wake: %ld turns, %.0f us of work per turn, spin %.0f us, %s\n", o.turns,
              o.work_us, o.spin_us, o.one_core ? "both on CPU 0" : "free to use both cores");
  std::fflush(stdout);
  pid_t child[2] = {-1, -1};
  for (int me = 0; me < 2; ++me) {
    child[me] = ::fork();
    if (child[me] < 0) {
      std::fprintf(stderr, "bench_wake: fork failed: %s\n", std::strerror(errno));
      return 2;
    }
    if (child[me] == 0) _exit(play(me, o, *turn, bells[me], bells[1 - me]));
  }
  int failed = 0;
  for (pid_t c : child) {
    int status = 0;
    if (::waitpid(c, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failed;
  }
  return failed == 0 ? 0 : 2;
}
