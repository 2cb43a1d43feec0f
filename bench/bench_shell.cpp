// Belytschko-Tsay shell kernel throughput: ns per element per cycle on a flat N x N plate (the
// argument: 316, 99 856 elements, the figures quoted; 119, 14 161, the 10 mm head impact's count;
// 40, 1 600, whose arrays fit in a core's L2) with small random velocities (elastic) or a uniform
// stretch that keeps every point plastic (J2, 5 through-thickness points), without and with
// stiffness-proportional damping (Part::damping_ratio = 0.05; the undamped variants must not pay
// for it). One kernel call = one cycle of the part.
// Counters: ns_per_element (time per element and cycle), bytes_per_element (element history
// ShellState + connectivity; the nodal arrays x, v, omega, f, m add 120 B per node, about one node
// per element), plastic_fraction (elements with every through-thickness point yielded).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "solver/elements/shell_bt.h"

namespace {

namespace model = crashlink::model;
namespace materials = crashlink::materials;
namespace el = crashlink::elements;

constexpr double kA = 0.005;  // element edge [m]

struct Plate {
  model::Part part;
  std::vector<double> x, v, w, f, m;
};

Plate make_plate(int kN, int points, bool stretch, double damping_ratio) {
  Plate p;
  const std::size_t nn = static_cast<std::size_t>(kN + 1) * (kN + 1);
  p.x.resize(3 * nn);
  p.v.resize(3 * nn);
  p.w.resize(3 * nn);
  p.f.assign(3 * nn, 0.0);
  p.m.assign(3 * nn, 0.0);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) {
      const std::size_t n = static_cast<std::size_t>(j * (kN + 1) + i);
      p.x[3 * n] = i * kA;
      p.x[3 * n + 1] = j * kA;
      p.x[3 * n + 2] = 0.0;
      for (int c = 0; c < 3; ++c) {
        p.v[3 * n + static_cast<std::size_t>(c)] = 0.1 * u(rng);   // [m/s]
        p.w[3 * n + static_cast<std::size_t>(c)] = 10.0 * u(rng);  // [rad/s]
      }
      if (stretch) {  // biaxial-ish stretch rate 200 /s plus the noise: plastic every cycle
        p.v[3 * n] += 200.0 * p.x[3 * n];
        p.v[3 * n + 1] += 50.0 * p.x[3 * n + 1];
      }
    }
  p.part.name = "plate";
  p.part.kind = model::ElementKind::Shell4;
  p.part.thickness_m = 0.001;
  p.part.through_thickness_points = points;
  p.part.damping_ratio = damping_ratio;
  p.part.connectivity.reserve(4 * static_cast<std::size_t>(kN) * kN);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const int a = j * (kN + 1) + i;
      p.part.connectivity.insert(p.part.connectivity.end(), {a, a + 1, a + kN + 2, a + kN + 1});
      p.part.element_id.push_back(a);
    }
  return p;
}

void run(benchmark::State& state, const materials::Material& mat, int points, bool stretch,
         double damping_ratio = 0.0) {
  Plate p = make_plate(static_cast<int>(state.range(0)), points, stretch, damping_ratio);
  el::ShellState st = el::make_shell_state(p.part);
  const el::NodalView nv{p.x.data(), p.v.data(), p.w.data(), p.f.data(), p.m.data()};
  const el::StepInfo step{5e-7};  // strain increment 1e-4 per cycle for the stretch
  for (int i = 0; i < 30; ++i) el::shell_internal_forces(p.part, mat, st, nv, step);  // warm up
  for (auto _ : state) {
    auto r = el::shell_internal_forces(p.part, mat, st, nv, step);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double ne = static_cast<double>(p.part.element_count());
  state.counters["ns_per_element"] = benchmark::Counter(
      ne * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  // History as the kernel leaves it: point form (J2) or resultant form (elastic), see shell_bt.h.
  const double bytes =
      static_cast<double>(8 * (st.sigma_Pa.size() + st.eps_p.size() + st.resultant_Pa.size() +
                               st.shear_Pa.size() + st.thickness_m.size() + st.hourglass.size() +
                               st.damping_beta_s.size() + st.damping_stress_Pa.size()) +
                          4 * p.part.connectivity.size());
  state.counters["bytes_per_element"] = bytes / ne;
  double plastic = 0.0;  // elements whose every point has yielded
  for (std::size_t e = 0; e < st.element_count; ++e) {
    bool all = true;
    for (int k = 0; k < st.points; ++k) all = all && st.plastic_strain(k, e) > 0.0;
    plastic += all ? 1.0 : 0.0;
  }
  state.counters["plastic_fraction"] = plastic / ne;
}

materials::Material steel(bool plastic) {
  materials::Material m{
      "steel", plastic ? materials::MaterialKind::J2Plastic : materials::MaterialKind::Elastic,
      7850.0,  210e9,
      0.3,     {}};
  if (plastic) m.hardening = {{0.0, 0.02, 0.1, 0.5}, {250e6, 300e6, 380e6, 500e6}};
  return m;
}

void BM_ShellElastic3(benchmark::State& s) {
  run(s, steel(false), 3, false);
}
void BM_ShellElastic5(benchmark::State& s) {
  run(s, steel(false), 5, false);
}
void BM_ShellPlastic5(benchmark::State& s) {
  run(s, steel(true), 5, true);
}
// With Cowper-Symonds rate scaling (C 40.4 1/s, P 5): one pow per yielding batch's point.
void BM_ShellPlastic5Rate(benchmark::State& s) {
  auto m = steel(true);
  m.rate_c_per_s = 40.4;
  m.rate_p = 5.0;
  run(s, m, 5, true);
}
void BM_ShellElastic5Damped(benchmark::State& s) {
  run(s, steel(false), 5, false, 0.05);
}
void BM_ShellPlastic5Damped(benchmark::State& s) {
  run(s, steel(true), 5, true, 0.05);
}

/// The plates, N x N elements: 100k (the figures quoted), the 10 mm head impact's count, and one
/// in a core's L2.
void plate_sizes(benchmark::internal::Benchmark* b) {
  b->Arg(316)->Arg(119)->Arg(40);
}

}  // namespace

BENCHMARK(BM_ShellElastic3)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShellElastic5)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShellPlastic5)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShellPlastic5Rate)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShellElastic5Damped)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShellPlastic5Damped)->Apply(plate_sizes)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
