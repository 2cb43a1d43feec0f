#pragma once
// Shared by the round-trip benchmarks (bench_transport, bench_lane): the interface sizes they run
// (100, 1 000 and 10 000 nodes, wall-clock µs) and the median_us / p99_us counters over every
// round trip of a run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

namespace crashlink::bench {

inline void interface_sizes(benchmark::internal::Benchmark* b) {
  b->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond)->UseRealTime();
}

/// Sorts `us` (one entry per round trip, µs) and sets the median_us and p99_us counters.
inline void report_round_trips(benchmark::State& state, std::vector<double>& us) {
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  state.counters["median_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

/// One call of `trip` (a round trip; false when it failed) per benchmark iteration, each timed;
/// a failed one ends the run with `error`. Then the counters.
template <class Trip>
void time_round_trips(benchmark::State& state, Trip&& trip, const char* error) {
  std::vector<double> us;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!trip()) {
      state.SkipWithError(error);
      break;
    }
    us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
  }
  report_round_trips(state, us);
}

}  // namespace crashlink::bench
