#include "solver/parallel/thread_team.h"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>

#include "core/errors.h"

namespace crashlink::parallel {

namespace {

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

/// Waits until `a` no longer holds `old`: spins for up to `spin_ns`, then sleeps
/// (std::atomic::wait, a futex), counted in `sleepers` so that the writer of `a` calls the kernel
/// only when someone sleeps (wake_if_asleep: both sides sequentially consistent, so either the
/// writer sees the sleeper or the sleeper sees the new value). The spin adapts: halved after a
/// wait that had to sleep, doubled (up to `max_ns`) after one the spin ended. On a machine whose
/// cores are busy with other work the partner is often off its core, and a spin would only keep
/// it off longer.
template <class T>
T wait_change(const std::atomic<T>& a, T old, std::int64_t& spin_ns, std::int64_t max_ns,
              std::atomic<int>& sleepers) {
  if (spin_ns > 0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::nanoseconds(spin_ns);
    for (int i = 0;; ++i) {
      const T now = a.load(std::memory_order_acquire);
      if (now != old) {
        spin_ns = std::min(max_ns, 2 * spin_ns + 1000);
        return now;
      }
      cpu_relax();
      if ((i & 63) == 63 && std::chrono::steady_clock::now() >= until) break;
    }
  }
  spin_ns = max_ns > 0 ? std::max<std::int64_t>(1000, spin_ns / 2) : 0;
  T now;
  sleepers.fetch_add(1, std::memory_order_seq_cst);
  while ((now = a.load(std::memory_order_seq_cst)) == old) a.wait(old, std::memory_order_seq_cst);
  sleepers.fetch_sub(1, std::memory_order_relaxed);
  return now;
}

template <class T>
void wake_if_asleep(std::atomic<T>& a, const std::atomic<int>& sleepers) {
  if (sleepers.load(std::memory_order_seq_cst) > 0) a.notify_all();
}

}  // namespace

ThreadTeam::ThreadTeam(int threads) {
  if (threads < 1 || threads > 1024)
    throw ModelError(fmt::format(
        "a solver's thread count must be between 1 and 1024, not {}; use --threads 0 for one "
        "thread per core this process may use",
        threads));
  // A spin saves the futex round trip between the loops of a cycle; with more threads than cores
  // a spinning thread only keeps the one with work off its core: then none.
  spin_ns_ = threads <= available_cores() ? kSpinNs : 0;
  caller_spin_ns_ = spin_ns_;
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  try {
    for (int k = 1; k < threads; ++k)
      workers_.emplace_back([this, k] { work_loop(static_cast<std::size_t>(k)); });
  } catch (...) {  // a thread refused (a limit): stop and join those started, then say so
    stop_workers();
    throw;
  }
}

ThreadTeam::~ThreadTeam() {
  stop_workers();
}

void ThreadTeam::stop_workers() {
  stop_.store(true, std::memory_order_seq_cst);
  generation_.fetch_add(1, std::memory_order_seq_cst);
  generation_.notify_all();
  for (auto& w : workers_)
    if (w.joinable()) w.join();
}

double ThreadTeam::workers_cpu_seconds() {
  double s = 0.0;
  for (auto& w : workers_) {
    clockid_t id{};
    timespec ts{};
    if (pthread_getcpuclockid(w.native_handle(), &id) == 0 && clock_gettime(id, &ts) == 0)
      s += static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  return s;
}

void ThreadTeam::run(std::size_t count, TaskFn fn, void* ctx, bool per_thread) {
  if (count == 0) return;
  if (workers_.empty() || (count == 1 && !per_thread)) {
    for (std::size_t t = 0; t < count; ++t) fn(ctx, t);
    return;
  }
  fn_ = fn;
  ctx_ = ctx;
  count_ = count;
  per_thread_ = per_thread;
  next_.store(0, std::memory_order_relaxed);
  running_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_seq_cst);
  wake_if_asleep(generation_, workers_asleep_);
  if (per_thread)
    call(0);
  else
    take_tasks();
  for (int r = running_.load(std::memory_order_acquire); r != 0;)
    r = wait_change(running_, r, caller_spin_ns_, spin_ns_, caller_asleep_);
  if (error_) {
    std::exception_ptr e;
    std::swap(e, error_);
    std::rethrow_exception(e);
  }
}

void ThreadTeam::take_tasks() {
  for (;;) {
    const std::size_t t = next_.fetch_add(1, std::memory_order_relaxed);
    if (t >= count_) return;
    call(t);
  }
}

void ThreadTeam::call(std::size_t task) {
  try {
    fn_(ctx_, task);
  } catch (...) {
    const std::lock_guard<std::mutex> lock(error_mutex_);
    if (!error_) error_ = std::current_exception();
    next_.store(count_, std::memory_order_relaxed);  // the rest is not worth computing
  }
}

void ThreadTeam::work_loop(std::size_t index) {
  std::uint64_t seen = 0;
  std::int64_t spin_ns = spin_ns_;
  for (;;) {
    seen = wait_change(generation_, seen, spin_ns, spin_ns_, workers_asleep_);
    if (stop_.load(std::memory_order_seq_cst)) return;
    if (per_thread_)
      call(index);
    else
      take_tasks();
    if (running_.fetch_sub(1, std::memory_order_seq_cst) == 1)
      wake_if_asleep(running_, caller_asleep_);
  }
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return 1;
  const int n = CPU_COUNT(&set);
  return n > 0 ? n : 1;
}

}  // namespace crashlink::parallel
