// The core's measured arithmetic peak, against which the element kernels' rates are quoted
// (docs/benchmarks.md "The arithmetic bound"): chains of independent fused
// multiply-adds on 256-bit vectors of 4 doubles (the Release build's x86-64-v3), 2 flops per lane
// each. 12 independent accumulators cover the FMA latency (4 cycles) times the two FMA ports of
// current x86 cores, so the loop runs at the issue rate. Counter: gflops (per second of CPU).
#include <benchmark/benchmark.h>

#include <cstdint>

#if defined(__FMA__) && defined(__AVX__)
#include <immintrin.h>

namespace {

constexpr int kChains = 12;
constexpr std::int64_t kInner = 4096;  // FMAs per chain per iteration

void BM_FmaPeak256(benchmark::State& state) {
  __m256d acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm256_set1_pd(1.0 + 1e-3 * c);
  // a * acc + b with |a| < 1: the values stay bounded, no denormals, no overflow
  const __m256d a = _mm256_set1_pd(0.999999), b = _mm256_set1_pd(1e-6);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < kInner; ++i)
      for (int c = 0; c < kChains; ++c) acc[c] = _mm256_fmadd_pd(a, acc[c], b);
    for (int c = 0; c < kChains; ++c) benchmark::DoNotOptimize(acc[c]);
  }
  const double flops = 2.0 * 4.0 * kChains * static_cast<double>(kInner);
  state.counters["gflops"] =
      benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_FmaPeak256);
#endif

BENCHMARK_MAIN();
