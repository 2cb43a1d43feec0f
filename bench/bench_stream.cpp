// The core's measured streaming rate, against which the nodal passes' cost is quoted
// (docs/benchmarks.md "The nodal passes' floor"): the STREAM triad c = a + s b (McCalpin, STREAM
// benchmark) over three arrays of N doubles each, from sizes that stay in a core's L2 to sizes
// that stream from memory. Counters: gb_per_s counts the 3 N doubles the loop names (STREAM's
// convention); with_rfo_gb_per_s adds the read-for-ownership of c, which a store to a line not in
// the cache costs (4 N doubles), as the nodal passes' arrays that are only written pay it.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

void BM_Triad(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 0.0);
  const double s = 0.5;
  for (auto _ : state) {
    const double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pc[i] = pa[i] + s * pb[i];
    benchmark::DoNotOptimize(pc);
    benchmark::ClobberMemory();
  }
  const double bytes = 8.0 * static_cast<double>(n);
  state.counters["gb_per_s"] =
      benchmark::Counter(3.0 * bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["with_rfo_gb_per_s"] =
      benchmark::Counter(4.0 * bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

// 3 arrays of 16 k doubles: 384 kB (a core's L2); of 1 M: 24 MB; of 8 M: 192 MB (memory, or
// the shared L3 of a large host in part). The 2.5 mm scale scene's node arrays hold 0.9 M
// doubles each.
BENCHMARK(BM_Triad)->Arg(16 << 10)->Arg(1 << 20)->Arg(8 << 20);

}  // namespace

BENCHMARK_MAIN();
