// Hex8 kernel throughput: ns per element per cycle of hex8_internal_forces on a box of hexahedra
// (the arguments: 100 x 100 x 10, 100k, the figures quoted; 60 x 60 x 4, 14 400; 20 x 20 x 4,
// 1 600, whose arrays fit in a core's L2; edge 1 cm, steel), small random velocities, elastic and
// J2, without and with stiffness-proportional damping (Part::damping_ratio = 0.05; the undamped
// variants must not pay for it).
// Counters: ns_per_element, state_bytes_per_element (history + connectivity).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"

namespace {

namespace el = crashlink::elements;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

struct Box {
  crashlink::model::Part part;
  std::vector<double> x, v, f;
};

Box make_box(int nx, int ny, int nz, double h) {
  Box b;
  b.part.name = "box";
  auto id = [&](int i, int j, int k) {
    return static_cast<std::int32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        b.x.insert(b.x.end(), {i * h, j * h, k * h});
        b.v.insert(b.v.end(), {u(gen), u(gen), u(gen)});  // [m/s]
      }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        for (int kk = 0; kk < 2; ++kk)
          b.part.connectivity.insert(b.part.connectivity.end(),
                                     {id(i, j, k + kk), id(i + 1, j, k + kk),
                                      id(i + 1, j + 1, k + kk), id(i, j + 1, k + kk)});
        b.part.element_id.push_back(static_cast<std::int64_t>(b.part.element_id.size()) + 1);
      }
  b.f.assign(b.x.size(), 0.0);
  return b;
}

void run(benchmark::State& state, const Material& mat, double damping_ratio = 0.0) {
  Box b = make_box(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                   static_cast<int>(state.range(2)), 0.01);
  b.part.damping_ratio = damping_ratio;
  auto st = el::make_hex8_state(b.part);
  el::NodalView nv{b.x.data(), b.v.data(), nullptr, b.f.data(), nullptr};
  el::StepInfo step;
  el::hex8_internal_forces(b.part, mat, st, nv, step);  // initial call
  step.dt_s = 1e-7;
  const auto ne = static_cast<double>(b.part.element_count());
  for (auto _ : state) {
    auto r = el::hex8_internal_forces(b.part, mat, st, nv, step);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_element"] =
      benchmark::Counter(ne * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["state_bytes_per_element"] =
      static_cast<double>(el::Hex8State::bytes_per_element() + 8 * sizeof(std::int32_t) +
                          (b.part.damped() ? el::Hex8State::damping_bytes_per_element() : 0));
  double ep = 0.0;
  for (double e : st.eps_p) ep = std::max(ep, e);
  state.counters["max_eps_p"] = ep;
}

void BM_Hex8Elastic(benchmark::State& state) {
  run(state, {"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
}
void BM_Hex8ElasticDamped(benchmark::State& state) {
  run(state, {"steel", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}}, 0.05);
}
// Low yield stress so that the elements go plastic within the first iterations (random
// velocities 1 m/s over h = 1 cm: strain rate ~100/s, 1e-5 per cycle).
void BM_Hex8J2(benchmark::State& state) {
  run(state,
      {"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.1, 1.0}, {2e6, 5e6, 6e6}}});
}
// The same with Cowper-Symonds rate scaling (mild steel C 40.4 1/s, P 5): one pow per element.
void BM_Hex8J2Rate(benchmark::State& state) {
  Material m{"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.1, 1.0}, {2e6, 5e6, 6e6}}};
  m.rate_c_per_s = 40.4;
  m.rate_p = 5.0;
  run(state, m);
}
void BM_Hex8J2Damped(benchmark::State& state) {
  run(state,
      {"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.1, 1.0}, {2e6, 5e6, 6e6}}},
      0.05);
}

/// The boxes, nx x ny x nz elements: 100k (the figures quoted), the 10 mm head impact's count,
/// and one in a core's L2.
void box_sizes(benchmark::internal::Benchmark* b) {
  b->Args({100, 100, 10})->Args({60, 60, 4})->Args({20, 20, 4});
}

}  // namespace

BENCHMARK(BM_Hex8Elastic)->Apply(box_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hex8J2)->Apply(box_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hex8J2Rate)->Apply(box_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hex8ElasticDamped)->Apply(box_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hex8J2Damped)->Apply(box_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
