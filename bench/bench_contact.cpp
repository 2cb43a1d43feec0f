// Contact cost per tested node per cycle, one-pass, two-pass and single-surface
// (ContactInterface::compute: travel check, re-sorts when due, projection, forces) against the
// master surface size (10k, 100k, 1M segments): the scene and what is timed are on
// BM_ContactPerSlaveNode, the figures in docs/benchmarks.md "Contact".
#include <benchmark/benchmark.h>
#include <time.h>

#include <random>

#include "core/cpu_clock.h"
#include "solver/contact/contact_interface.h"
#include "solver/model/mesh_generators.h"

using namespace crashlink;

namespace {

constexpr double kH = 0.005;  // element size [m]
constexpr double kT = 0.001;  // shell thickness [m]
constexpr double kDt = 1e-6;  // step [s]

/// range(0) = n: a square plate of n x n shell segments and the nodes of a second plate of the
/// same size and pitch, offset by a third of an element in plane, hovering at the contact
/// distance with a random vertical jitter of +-5 % of the element size so that about half of them
/// are in contact. Each cycle the slave nodes move by a random velocity of up to 2e-3 element
/// sizes per step and bounce in a +-5 % band vertically, so that a re-sort is due every ~88
/// cycles (margin/2 = 0.177 element sizes of travel; about the rate in a crash run): 100 timed
/// cycles hold one at every size. The numbering is the plate generator's, row by row, as a mesher
/// numbers a structured plate; slave and master are separate blocks, as two parts are.
/// range(1): 0 node-to-surface (one pass), 1 surface-to-surface (two passes: also the master
/// plate's nodes against the slave plate's faces), 2 single-surface over both plates (every node
/// against every other segment). Items = the nodes the passes test, x cycles: the reported
/// items_per_second inverted is ns/node/cycle. Only ContactInterface::compute is timed (manual
/// time), in the thread's CPU time: the harness's own passes over the nodes (moving the slaves,
/// zeroing f) stream 3n-long arrays that fit the cache at 10k and not at 1M and would count as
/// contact growth, and on a machine shared with other jobs the wall time also counts the time
/// slices others take.
void BM_ContactPerSlaveNode(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto kind = static_cast<model::ContactKind>(state.range(1) == 0   ? 0
                                                    : state.range(1) == 1 ? 1
                                                                          : 2);
  model::Model m;
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
  model::Part p;
  p.material = 0;
  p.thickness_m = kT;
  p.name = "master";
  const double L = n * kH;
  model::generate_plate(m, p, {{0, 0, 0}, {L, 0, 0}, {0, L, 0}, {n, n}, 0.0});
  const std::size_t n_master = m.nodes.count();
  p.name = "slave";
  model::generate_plate(m, p, {{kH / 3, kH / 3, kT}, {L, 0, 0}, {0, L, 0}, {n, n}, 0.0});
  const std::size_t nn = m.nodes.count();
  model::Contact c;
  c.name = "plates";
  c.kind = kind;
  c.master_parts = {0};
  if (kind == model::ContactKind::SingleSurface)
    c.master_parts = {0, 1};
  else
    for (std::size_t i = n_master; i < nn; ++i)
      c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  std::vector<double> mass(nn, 7850.0 * kT * kH * kH), x = m.nodes.x0, v(3 * nn, 0.0), f(3 * nn);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double band = 0.05 * kH, speed = 2e-3 * kH / kDt;
  for (std::size_t i = n_master; i < nn; ++i) {
    x[3 * i + 2] += band * u(rng);
    for (std::size_t d = 0; d < 3; ++d) v[3 * i + d] = speed * u(rng) / std::sqrt(3.0);
  }
  contact::ContactInterface ci(m, c, mass.data());
  ci.compute(x.data(), v.data(), 0.0, f.data());  // start-up sort, not part of the steady state
  const std::int64_t sorts0 = ci.sort_count();
  std::int64_t cycles = 0, active = 0;
  for (auto _ : state) {
    for (std::size_t i = n_master; i < nn; ++i) {
      for (std::size_t d = 0; d < 3; ++d) x[3 * i + d] += kDt * v[3 * i + d];
      const double z = x[3 * i + 2] - kT;
      if ((z > band && v[3 * i + 2] > 0.0) || (z < -band && v[3 * i + 2] < 0.0))
        v[3 * i + 2] = -v[3 * i + 2];
    }
    std::fill(f.begin(), f.end(), 0.0);
    const double t0 = core::thread_cpu_seconds();
    const auto step = ci.compute(x.data(), v.data(), kDt, f.data());
    const double t1 = core::thread_cpu_seconds();
    benchmark::DoNotOptimize(step);
    state.SetIterationTime(t1 - t0);
    active += step.active_pairs;
    ++cycles;
  }
  const auto ns = static_cast<std::int64_t>(
      kind == model::ContactKind::NodeToSurface      ? c.slave_nodes.size()
      : kind == model::ContactKind::SurfaceToSurface ? c.slave_nodes.size() + n_master
                                                     : nn);
  state.SetItemsProcessed(state.iterations() * ns);
  state.counters["segments"] = static_cast<double>(ci.segment_count());
  state.counters["slaves"] = static_cast<double>(ns);
  state.counters["active_frac"] = static_cast<double>(active) / static_cast<double>(cycles * ns);
  state.counters["sorts"] = static_cast<double>(ci.sort_count() - sorts0);
}

}  // namespace

BENCHMARK(BM_ContactPerSlaveNode)
    ->ArgsProduct({{100, 316, 1000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(100)  // the same cycles at every size: the same share of re-sorts (1 in 100)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK_MAIN();
