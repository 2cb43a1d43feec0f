#pragma once
// A fixed team of threads that runs the tasks of a loop: created once per solver, woken per
// loop, never created or allocated per step (docs/threads.md).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace crashlink::parallel {

/// `threads` - 1 worker threads plus the caller. for_each(count, f) calls f(task) once for every
/// task in [0, count), spread over the team (a shared counter hands the next task to whichever
/// thread is free); on_each_thread(f) calls f(t) once on each thread t (0: the caller, k: worker
/// k, always the same thread, so that what thread t writes stays in its core's cache from one
/// loop to the next). Both return when every call has returned. A call must write only what is
/// its own (its element or node range, its slot of a result array): the caller then combines
/// those in order, and the result is the same for every team size. The first exception a call
/// throws is rethrown after every call has ended. Not reentrant: one loop at a time, from the
/// thread that built the team.
class ThreadTeam {
 public:
  /// The longest a waiting thread spins before it sleeps on the futex [ns]: longer than most
  /// serial stretches between two loops of a cycle, far shorter than a time slice (measured in
  /// docs/threads.md). Adapted per wait; none when the team has more threads than the process
  /// has cores.
  static constexpr std::int64_t kSpinNs = 100000;

  explicit ThreadTeam(int threads);
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }
  /// CPU seconds the workers have used since they started (not the caller's: its thread's own
  /// clock has it), for a solver that runs as a thread of a bigger process.
  double workers_cpu_seconds();

  template <class F>
  void for_each(std::size_t count, F&& f) {
    using Fn = std::remove_reference_t<F>;
    run(
        count, [](void* ctx, std::size_t task) { (*static_cast<Fn*>(ctx))(task); },
        const_cast<void*>(static_cast<const void*>(&f)), false);
  }
  template <class F>
  void on_each_thread(F&& f) {
    using Fn = std::remove_reference_t<F>;
    run(
        static_cast<std::size_t>(size()),
        [](void* ctx, std::size_t t) { (*static_cast<Fn*>(ctx))(static_cast<int>(t)); },
        const_cast<void*>(static_cast<const void*>(&f)), true);
  }

 private:
  using TaskFn = void (*)(void*, std::size_t);
  void run(std::size_t count, TaskFn fn, void* ctx, bool per_thread);
  void work_loop(std::size_t index);
  void take_tasks();
  void call(std::size_t task);
  void stop_workers();

  std::vector<std::thread> workers_;
  TaskFn fn_ = nullptr;
  void* ctx_ = nullptr;
  std::size_t count_ = 0;
  bool per_thread_ = false;           ///< on_each_thread: worker k runs task k, the caller task 0
  std::atomic<std::size_t> next_{0};  ///< the next task to hand out
  std::atomic<std::uint64_t> generation_{0};  ///< bumped per loop and to stop
  std::atomic<bool> stop_{false};
  std::atomic<int> workers_asleep_{0};  ///< workers sleeping on generation_
  std::atomic<int> caller_asleep_{0};   ///< 1 while the caller sleeps on running_
  std::atomic<int> running_{0};         ///< workers still in the current loop
  std::int64_t spin_ns_ = 0;            ///< the longest a waiting thread spins before it sleeps
  std::int64_t caller_spin_ns_ = 0;     ///< the caller's spin now (adapted per wait)
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

/// The thread count that `--threads 0` means: the cores this process may run on
/// (sched_getaffinity, so a Slurm or container limit counts), at least 1.
int available_cores();

}  // namespace crashlink::parallel
