// Issue 24 item 1: a solver's element forces on 1 to 4 threads give the same run to the bit
// (integration::ElementChunks, docs/threads.md). Each scene runs the same cycles on every thread
// count and compares every nodal vector, the energies and the step bit by bit with one thread's:
//   * a J2 shell plate hit by a rigid sphere (contact with friction, both passes over blocks of
//     nodes on the team; plasticity, a damped strip: shells, the penalty step), 40 chunks over
//     many shared nodes;
//   * a hex block twisted by an initial spin about a clamped face (hexes, bulk viscosity);
//   * the head-impact CI scene, mono: the whole run to the bit, through run_single_domain.
// A scatter plan that let two threads add into one node, or a fold of the chunk results in the
// order they finished, changes these bits from one run to the next.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "solver/integration/element_chunks.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"
#include "solver/model/mesh_generators.h"
#include "tests/integration/contact_sphere_plate.h"
#include "tests/integration/contact_tube.h"
#include "tests/integration/test_models.h"

using namespace crashlink;

namespace {

/// What one run ends with, every value's bits.
struct Ending {
  std::vector<double> u, v, a, omega;
  std::vector<double> energies;  // kinetic, internal, hourglass, contact, external, damping
  double dt = 0.0, dt_stable = 0.0;
  std::string critical;
  std::vector<std::int64_t> active_pairs;  // per contact interface, the last cycle
};

Ending run(const model::Model& m, int threads, int cycles, bool store_every_increment = false) {
  integration::Solver s(m, "threads");
  s.set_threads(threads);
  s.store_every_increment(store_every_increment);
  s.initialize();
  for (int c = 0; c < cycles; ++c) {
    s.begin_cycle();
    s.end_cycle();
  }
  s.begin_cycle();
  Ending e{s.displacement(),
           s.velocity_mid(),
           s.acceleration(),
           s.angular_velocity_mid(),
           {},
           s.dt_s(),
           s.dt_stable_s(),
           s.critical_element(),
           {}};
  const auto& en = s.energy();
  e.energies = {en.kinetic_J, en.internal_J, en.hourglass_J, en.contact_J, en.external_work_J};
  for (const auto& p : s.parts()) e.energies.push_back(p.damping_energy_J);
  for (const auto& c : s.contact_steps()) {
    e.active_pairs.push_back(c.active_pairs);
    e.energies.push_back(c.energy_J);
  }
  return e;
}

/// Index of the first value whose bits differ, or -1.
long first_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i]))
      return static_cast<long>(i);
  return -1;
}

void expect_same(const Ending& one, const Ending& other, int threads) {
  EXPECT_EQ(first_difference(one.u, other.u), -1) << threads << " threads: u";
  EXPECT_EQ(first_difference(one.v, other.v), -1) << threads << " threads: v";
  EXPECT_EQ(first_difference(one.a, other.a), -1) << threads << " threads: a";
  EXPECT_EQ(first_difference(one.omega, other.omega), -1) << threads << " threads: omega";
  EXPECT_EQ(first_difference(one.energies, other.energies), -1) << threads << " threads: energy";
  EXPECT_EQ(std::bit_cast<std::uint64_t>(one.dt), std::bit_cast<std::uint64_t>(other.dt));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(one.dt_stable),
            std::bit_cast<std::uint64_t>(other.dt_stable));
  EXPECT_EQ(one.critical, other.critical);
  EXPECT_EQ(one.active_pairs, other.active_pairs) << threads << " threads: contact pairs";
}

/// The sphere on a 100 x 100 J2 plate, its middle rows damped; the sphere lands within the run.
/// Two contact passes with friction, each over several blocks of nodes (ContactPass::kBlockNodes):
/// the plate's 10 201 nodes against the sphere, the sphere's nodes against the plate.
model::Model sphere_on_plate() {
  crashlink::testing::SpherePlateSpec spec;
  spec.plate_divisions = 100;
  spec.j2 = true;
  spec.speed_m_s = 30.0;
  spec.sphere_divisions = 16;
  auto b = crashlink::testing::make_sphere_plate(spec);
  b.m.contacts[0].static_friction = 0.3;
  b.m.contacts[0].dynamic_friction = 0.2;
  auto& plate = b.m.parts[0];
  plate.element_damping_ratio.assign(plate.element_count(), 0.0);
  for (std::size_t e = 4000; e < 6000; ++e) plate.element_damping_ratio[e] = 0.05;
  return b.m;
}

/// A 30 x 20 x 6 steel block clamped at x = 0, spinning about the x axis (y = z = 0) at
/// 200 rad/s.
model::Model twisted_block() {
  return crashlink::testing::clamped_moving_block({0.0, -0.1, -0.03}, {0.3, 0.2, 0.06}, {30, 20, 6},
                                                  {}, {200.0, 0.0, 0.0});
}

}  // namespace

TEST(SolverThreads, ShellPlateUnderASphereIsTheSameToTheBitOn1To4Threads) {
  const auto m = sphere_on_plate();
  const auto one = run(m, 1, 400);
  // the run did what it is here to check: contact and plastic work
  ASSERT_GT(one.energies[3], 0.0) << "no contact energy: the sphere never landed";
  for (int t = 2; t <= 4; ++t) expect_same(one, run(m, t, 400), t);
}

// Single-surface contact on the team: a J2 square tube (1 721 nodes, 27 blocks of the self
// contact's nodes and 27 of the ram's) crushed at 30 m/s until its walls fold onto each other
// (the self contact's first pairs at cycle 1 359 on one thread).
TEST(SolverThreads, TubeFoldingOntoItselfIsTheSameToTheBitOn1And3Threads) {
  crashlink::testing::TubeSpec spec;
  spec.fine_length_m = 0.0;
  spec.ram_speed_m_s = 30.0;
  const auto tube = crashlink::testing::make_tube(spec);
  ASSERT_EQ(tube.m.contacts.back().kind, model::ContactKind::SingleSurface);
  const auto one = run(tube.m, 1, 1500);
  ASSERT_GT(one.active_pairs.back(), 0) << "the tube's walls never met: no self-contact pair";
  expect_same(one, run(tube.m, 3, 1500), 3);
}

TEST(SolverThreads, HexBlockIsTheSameToTheBitOn1To4Threads) {
  const auto m = twisted_block();
  const auto one = run(m, 1, 300);
  ASSERT_GT(one.energies[1], 0.0);
  for (int t = 2; t <= 4; ++t) expect_same(one, run(m, t, 300), t);
}

// The global stable step (Controls::global_stable_step): its products run on the team, its
// Lanczos sums in index order; 400 cycles take two refreshes.
TEST(SolverThreads, GlobalStableStepIsTheSameToTheBitOn1To3Threads) {
  auto m = sphere_on_plate();
  m.controls.global_stable_step = true;
  const auto one = run(m, 1, 400);
  ASSERT_GT(one.energies[3], 0.0) << "no contact energy: the sphere never landed";
  for (int t = 2; t <= 3; ++t) expect_same(one, run(m, t, 400), t);
}

// du and dtheta (Solver::du_at, dtheta_at): stored only on the tiles with ghost, rigid,
// prescribed or wall nodes, recomputed as dt v and dt omega where read elsewhere. Here the rigid
// sphere's tiles store them and the plate's do not; gravity makes both halves of the external
// work run over every tile, the frictional contact both halves of its work over the plate's
// nodes. Storing them everywhere must give the same run to the bit, on 1 and on 3 threads.
TEST(SolverThreads, IncrementsRecomputedWhereReadGiveTheStoredRunsBits) {
  auto m = sphere_on_plate();
  m.controls.gravity_m_s2 = {0.0, 0.0, -9.81};
  for (int t : {1, 3}) {
    const auto stored = run(m, t, 400, true);
    ASSERT_GT(stored.energies[3], 0.0) << "no contact energy: the sphere never landed";
    ASSERT_NE(stored.energies[4], 0.0) << "no external work: gravity did nothing";
    expect_same(stored, run(m, t, 400, false), t);
  }
}

TEST(SolverThreads, ChunksSplitTheElementsAndShareTheBoundaryNodes) {
  // The plate: 10 000 shells in 20 chunks of 512 (the last short); the nodes of the rows where
  // two chunks meet are shared, the others not; the rigid sphere has no chunks.
  const auto m = sphere_on_plate();
  integration::ElementChunks c;
  const std::vector<std::size_t> split = {m.parts[0].element_count(), m.parts[1].element_count()};
  c.build(m, split, {1, 0}, true);
  ASSERT_EQ(c.chunks(0).size(), 20u);
  EXPECT_TRUE(c.chunks(1).empty());
  for (std::size_t k = 0; k < 20; ++k) {
    EXPECT_EQ(c.chunks(0)[k].first, 512 * k);
    EXPECT_EQ(c.chunks(0)[k].end, std::min<std::size_t>(10000, 512 * (k + 1)));
  }
  EXPECT_GT(c.shared_nodes(0), 0u);
  EXPECT_LT(c.shared_nodes(0), m.nodes.count() / 2);
  // without the plan, no slots: the elements add into their nodes
  integration::ElementChunks direct;
  direct.build(m, split, {1, 0}, false);
  EXPECT_EQ(direct.scatter(0), nullptr);
  EXPECT_EQ(direct.shared_nodes(0), 0u);
}

// What the kernels cost (Solver::kernel_cost, /timing, the scale benchmark's ns per hex- and per
// shell-cycle): one cycle in kKernelSampleCycles times each kind's chunks on every thread, so the
// element-cycles counted are the sampled cycles times the kind's deformable elements, on any team;
// each kind gets its own time where a thread's run of chunks crosses from one kind to the other
// (the CI head impact: hexes and shells, a rigid headform); the global step's refreshes are timed
// on their own, and only when it is on.
TEST(SolverThreads, KernelCostCountsTheSampledCyclesOfEachKindOnAnyTeam) {
  auto mixed =
      io::read_scenario(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml");
  mixed.controls.global_stable_step = true;
  auto plate = sphere_on_plate();  // shells only (the sphere is rigid: no chunks)
  plate.controls.global_stable_step = true;
  const auto block = twisted_block();  // hexes only, no global step
  constexpr int kCycles = 250;         // a global step refresh within them (kRefreshCycles 200)
  constexpr std::int64_t kSampled = kCycles / integration::Solver::kKernelSampleCycles;
  for (const model::Model* m : {&std::as_const(mixed), &std::as_const(plate), &block}) {
    std::array<std::int64_t, 2> deformable{};  // [model::ElementKind]
    for (const auto& p : m->parts)
      if (m->materials[static_cast<std::size_t>(p.material)].kind != materials::MaterialKind::Rigid)
        deformable[static_cast<std::size_t>(p.kind)] +=
            static_cast<std::int64_t>(p.element_count());
    for (int threads : {1, 3}) {
      const std::string where = m->name + ", " + std::to_string(threads) + " threads";
      integration::Solver s(*m, "costs");
      s.set_threads(threads);
      s.initialize();
      for (int c = 0; c < kCycles; ++c) {
        s.begin_cycle();
        s.end_cycle();
      }
      const auto cost = s.kernel_cost();
      EXPECT_EQ(cost.sampled_cycles, kSampled) << where;
      std::array<double, 2> ns_per_element{};
      for (std::size_t k = 0; k < 2; ++k) {
        EXPECT_EQ(cost.element_cycles[k], kSampled * deformable[k]) << where << ", kind " << k;
        if (deformable[k] == 0) {
          EXPECT_EQ(cost.seconds[k], 0.0) << where << ", kind " << k;
        } else {
          EXPECT_GT(cost.seconds[k], 0.0) << where << ", kind " << k;
          ns_per_element[k] = 1e9 * cost.seconds[k] / static_cast<double>(cost.element_cycles[k]);
        }
      }
      // Both kinds cost tens to hundreds of ns per element (docs/benchmarks.md): time given to
      // the wrong kind at the crossing would leave one of them far off the other.
      if (deformable[0] > 0 && deformable[1] > 0) {
        const double ratio = ns_per_element[0] / ns_per_element[1];
        EXPECT_GT(ratio, 0.1) << where << ": hex " << ns_per_element[0] << " ns, shell "
                              << ns_per_element[1] << " ns";
        EXPECT_LT(ratio, 10.0) << where << ": hex " << ns_per_element[0] << " ns, shell "
                               << ns_per_element[1] << " ns";
      }
      if (m->controls.global_stable_step)
        EXPECT_GT(cost.global_step_seconds, 0.0) << where;
      else
        EXPECT_EQ(cost.global_step_seconds, 0.0) << where;
    }
  }
}
