// One whole mono cycle of a scene (Solver::begin_cycle + end_cycle: velocities, positions, element
// forces, contacts, accelerations, energy): ns per cycle and per node. The per-node part (the
// passes over the nodal arrays) is what this benchmark watches besides the kernels, which
// bench_shell / bench_hex8 / bench_contact measure on their own.
// Scenes: scenarios/head_impact.yaml (15 431 nodes, 14 172 elements, 3 contacts) and its CI
// variant, after 2 000 warm-up cycles (the headform is on the hood by then: contacts active).
// Counters: ns_per_cycle, ns_per_node (per cycle), nodes, elements. The argument is the solver's
// thread count (docs/threads.md); times are wall-clock (UseRealTime), CPU per cycle beside them.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"

using namespace crashlink;

namespace {

void BM_MonoCycle(benchmark::State& state, const std::string& file) {
  auto m = std::make_unique<model::Model>(
      io::read_scenario(std::string(CRASHLINK_SCENARIO_DIR) + "/" + file));
  m->domains.clear();
  m->controls.end_time_s = 1.0;  // never finished inside the benchmark
  integration::Solver solver(*m, "mono");
  solver.set_threads(static_cast<int>(state.range(0)));
  solver.initialize();
  for (int i = 0; i < 2000; ++i) {
    solver.begin_cycle();
    solver.end_cycle();
  }
  for (auto _ : state) {
    solver.begin_cycle();
    solver.end_cycle();
  }
  const double n = static_cast<double>(m->nodes.count());
  std::size_t elements = 0;
  for (const auto& p : m->parts) elements += p.element_count();
  state.SetItemsProcessed(state.iterations());
  state.counters["ns_per_cycle"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ns_per_node"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * n * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["nodes"] = n;
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["threads"] = static_cast<double>(state.range(0));
}

}  // namespace

BENCHMARK_CAPTURE(BM_MonoCycle, head_impact, std::string("head_impact.yaml"))
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MonoCycle, head_impact_small, std::string("head_impact_small.yaml"))
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
