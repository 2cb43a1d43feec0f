// parallel::ThreadTeam: every task runs exactly once per loop whatever the team size, the loop
// returns only when all have ended (their writes seen), a task's exception reaches the caller
// after the others ended, and the team is reused loop after loop without new threads.
#include "solver/parallel/thread_team.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"

using crashlink::parallel::ThreadTeam;

TEST(ThreadTeam, EveryTaskRunsOncePerLoopOnEveryTeamSize) {
  for (int threads = 1; threads <= 5; ++threads) {
    ThreadTeam team(threads);
    EXPECT_EQ(team.size(), threads);
    for (std::size_t count : {0u, 1u, 2u, 3u, 7u, 64u, 1000u}) {
      std::vector<int> hits(count, 0);  // plain ints: the loop's end must publish them
      for (int loop = 0; loop < 50; ++loop) team.for_each(count, [&](std::size_t t) { ++hits[t]; });
      for (std::size_t t = 0; t < count; ++t)
        ASSERT_EQ(hits[t], 50) << threads << " threads, task " << t << " of " << count;
    }
  }
}

TEST(ThreadTeam, TheTasksSpreadOverTheTeam) {
  // Tasks that wait until a second thread has joined in: only a team that really runs on more
  // than one thread ends this loop (a 1 s cap keeps a failure from hanging).
  ThreadTeam team(2);
  std::mutex m;
  std::set<std::thread::id> seen;
  std::atomic<int> started{0};
  team.for_each(2, [&](std::size_t) {
    {
      const std::lock_guard<std::mutex> lock(m);
      seen.insert(std::this_thread::get_id());
    }
    started.fetch_add(1);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (started.load() < 2 && std::chrono::steady_clock::now() < until)
      std::this_thread::yield();
  });
  EXPECT_EQ(seen.size(), 2u);
}

TEST(ThreadTeam, ATasksExceptionReachesTheCallerAfterTheLoop) {
  ThreadTeam team(3);
  std::atomic<int> ran{0};
  EXPECT_THROW(team.for_each(100,
                             [&](std::size_t t) {
                               ran.fetch_add(1);
                               if (t == 10) throw std::runtime_error("task 10");
                             }),
               std::runtime_error);
  EXPECT_GE(ran.load(), 11);
  // and the team still works
  std::vector<int> hits(100, 0);
  team.for_each(100, [&](std::size_t t) { ++hits[t]; });
  for (int h : hits) EXPECT_EQ(h, 1);
}

TEST(ThreadTeam, ABadSizeIsRefusedWithTheFix) {
  try {
    ThreadTeam team(0);
    FAIL() << "0 threads accepted";
  } catch (const crashlink::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("--threads 0"), std::string::npos) << e.what();
  }
  EXPECT_GE(crashlink::parallel::available_cores(), 1);
}
