// Issue 24 item 1: no allocation per step from the threads. Counts every operator new of this
// test binary while a solver runs cycles after its first ones: the twisted hex block (no contact)
// allocates nothing per cycle on 1 or 3 threads, and the sphere on the plate (contact) as much on
// 3 threads as on 1.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "solver/integration/solver.h"
#include "solver/model/mesh_generators.h"
#include "tests/integration/contact_sphere_plate.h"
#include "tests/integration/test_models.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Every allocation of this binary is counted (harmless to the other tests: one relaxed add).
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

using namespace crashlink;

namespace {

/// Allocations during cycles [warm, warm + cycles) of a run of `m` on `threads` threads.
long allocations_per_run(const model::Model& m, int threads, int warm, int cycles) {
  integration::Solver s(m, "alloc");
  s.set_threads(threads);
  s.initialize();
  for (int c = 0; c < warm; ++c) {
    s.begin_cycle();
    s.end_cycle();
  }
  const long before = g_allocations.load();
  for (int c = 0; c < cycles; ++c) {
    s.begin_cycle();
    s.end_cycle();
  }
  return g_allocations.load() - before;
}

/// A 20 x 20 x 5 steel block clamped at x = 0, thrown at 5 m/s along z.
model::Model block() {
  return crashlink::testing::clamped_moving_block({0.0, 0.0, 0.0}, {0.2, 0.1, 0.05}, {20, 20, 5},
                                                  {0.0, 0.0, 5.0}, {});
}

}  // namespace

TEST(SolverThreadsAllocation, NonePerCycleOnOneOrThreeThreads) {
  const auto m = block();
  EXPECT_EQ(allocations_per_run(m, 1, 5, 200), 0);
  EXPECT_EQ(allocations_per_run(m, 3, 5, 200), 0);
}

TEST(SolverThreadsAllocation, ThreadsAddNoneToAContactRun) {
  crashlink::testing::SpherePlateSpec spec;
  spec.plate_divisions = 60;
  spec.speed_m_s = 30.0;
  const auto m = crashlink::testing::make_sphere_plate(spec).m;
  const long one = allocations_per_run(m, 1, 5, 150);
  EXPECT_EQ(allocations_per_run(m, 3, 5, 150), one);
  std::printf(
      "[measured] sphere on plate: %ld allocations in 150 cycles (contact), the same on 3 "
      "threads\n",
      one);
}
