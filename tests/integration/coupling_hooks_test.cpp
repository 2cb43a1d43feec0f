// The Solver's coupling hooks, driven by hand in one process: a bar of 20 hexes cut between
// elements 9 and 10 and coupled with the `layer` scheme of docs/design.md §2.7 at a common step
// must reproduce the single-domain run to round-off (issue 4: split vs mono <= 1e-10 after 10^4
// steps).
//
//   A (fine side)  : elements 0..9 plus the coarse side's first layer, element 10; node plane 11
//                    (J) is a ghost whose displacement comes from C.
//   C (coarse side): elements 11..19; J owned with its natural mass (elements 10 and 11).
//   Per cycle: C moves (u_J^{n+1}); A moves with J prescribed; A's force on J joins C's ([8]:
//   both forces over J's mass); both accelerate; the common step is the smaller proposal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "core/errors.h"
#include "solver/integration/solver.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

constexpr double kH = 0.01;  // element length [m]
constexpr double kA = 0.01;  // cross-section side [m]

model::Model bar_piece(int first_element, int elements, bool loaded) {
  auto m = bar(elements, elements * kH, kA, steel(0.3));
  for (std::size_t i = 0; i < m.nodes.count(); ++i) m.nodes.x0[3 * i] += first_element * kH;
  if (loaded) {  // a force pulse on the end x = 0: 1 kN per node for 20 us
    auto end = nodes_where(m, [](const Vec3& x) { return x[0] < 1e-12; });
    m.loads.push_back({"pulse", end, 0, model::Curve{{0.0, 2e-5, 2.1e-5}, {1e3, 1e3, 0.0}}});
  }
  m.controls.end_time_s = 1.0;  // the cycle count ends the run
  // The hooks are under test here, not the viscosity (whose energy accounting has its own test,
  // energy_accounting_test.cpp): without it each domain's balance closes to ~1e-4.
  m.controls.bulk_viscosity = false;
  return m;
}

/// Indices of the nodes of `m` on the plane x = x_plane, sorted by (y, z).
std::vector<std::int32_t> plane(const model::Model& m, double x_plane) {
  auto v = nodes_where(m, [&](const Vec3& x) { return std::abs(x[0] - x_plane) < 1e-9; });
  std::sort(v.begin(), v.end(), [&](std::int32_t a, std::int32_t b) {
    const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
    return std::make_pair(m.nodes.x0[3 * ia + 1], m.nodes.x0[3 * ia + 2]) <
           std::make_pair(m.nodes.x0[3 * ib + 1], m.nodes.x0[3 * ib + 2]);
  });
  return v;
}

}  // namespace

TEST(CouplingHooks, LayerSplitAtCommonStepReproducesMono) {
  const int cycles = 10000;
  auto mono_model = bar_piece(0, 20, true);
  integration::Solver mono(mono_model);
  mono.initialize();

  auto a_model = bar_piece(0, 11, true);   // elements 0..10 (10 = the moved layer)
  auto c_model = bar_piece(11, 9, false);  // elements 11..19
  const auto j_a = plane(a_model, 11 * kH), j_c = plane(c_model, 11 * kH);
  const auto j_mono = plane(mono_model, 11 * kH);
  ASSERT_EQ(j_a.size(), 4u);
  ASSERT_EQ(j_c.size(), 4u);
  integration::Solver a(a_model, "fine");
  integration::Solver c(c_model, "coarse");
  a.set_ghost_nodes(j_a);
  {  // J's natural mass: the lumped mass of the whole bar at that node (mono's)
    std::vector<double> m_over(c_model.nodes.count(), 0.0);
    for (std::size_t k = 0; k < 4; ++k)
      m_over[static_cast<std::size_t>(j_c[k])] = mono.mass()[static_cast<std::size_t>(j_mono[k])];
    c.set_mass_override(m_over);
  }
  a.initialize();
  c.initialize();
  auto common_step = [&] {
    const double dt = std::min(a.dt_s(), c.dt_s());
    a.impose_step(dt);
    c.impose_step(dt);
    mono.impose_step(dt);  // mono's own proposal is the same min: impose it to be explicit
  };
  common_step();
  std::vector<double> u_j(12);
  for (int n = 0; n < cycles; ++n) {
    mono.begin_cycle();
    a.begin_cycle();
    c.begin_cycle();
    mono.end_cycle();
    c.end_cycle_forces();
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t d = 0; d < 3; ++d)
        u_j[3 * k + d] = c.displacement()[3 * static_cast<std::size_t>(j_c[k]) + d];
    a.set_ghost_displacement(u_j.data());
    a.end_cycle_forces();
    for (std::size_t k = 0; k < 4; ++k)
      c.add_coupling_force(static_cast<std::size_t>(j_c[k]),
                           a.net_force(static_cast<std::size_t>(j_a[k])));
    c.end_cycle_accelerations();
    a.end_cycle_accelerations();
    common_step();
  }
  // Energies are complete at t^n after begin_cycle() (solver.h): read them there.
  mono.begin_cycle();
  a.begin_cycle();
  c.begin_cycle();
  // Compare every node by position (A's nodes are mono's first 12 planes, C's the last 10).
  double scale = 0.0, worst = 0.0;
  for (double u : mono.displacement()) scale = std::max(scale, std::abs(u));
  auto compare = [&](const integration::Solver& s, const model::Model& m) {
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      const Vec3 x{m.nodes.x0[3 * i], m.nodes.x0[3 * i + 1], m.nodes.x0[3 * i + 2]};
      const auto same = nodes_where(mono_model, [&](const Vec3& y) { return norm(y - x) < 1e-9; });
      ASSERT_EQ(same.size(), 1u);
      for (std::size_t d = 0; d < 3; ++d)
        worst = std::max(worst,
                         std::abs(s.displacement()[3 * i + d] -
                                  mono.displacement()[3 * static_cast<std::size_t>(same[0]) + d]));
    }
  };
  compare(a, a_model);
  compare(c, c_model);
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(worst / scale, 1e-10);
  // Energy: the two domains' energies add up to mono's; the coupling work cancels between them.
  const auto &ea = a.energy(), &ec = c.energy(), &em = mono.energy();
  const double e_split =
      ea.kinetic_J + ec.kinetic_J + ea.internal_J + ec.internal_J + ea.hourglass_J + ec.hourglass_J;
  const double e_mono = em.kinetic_J + em.internal_J + em.hourglass_J;
  EXPECT_NEAR(e_split, e_mono, 1e-9 * e_mono);
  EXPECT_NEAR(ea.coupling_work_J + ec.coupling_work_J, 0.0, 1e-6 * em.external_work_J);
  // Each domain balances on its own once the coupling work is counted (same bound as mono's:
  // the variable step leaves an O(dt change) residual, here ~1e-4).
  EXPECT_LT(std::abs(em.balance_error()), 1e-3);
  EXPECT_LT(std::abs(ea.balance_error()), 1e-3);
  EXPECT_LT(std::abs(ec.balance_error()), 1e-3);
  std::printf(
      "[measured] layer split vs mono, 1e4 steps: max |du|/max|u| = %.3e; coupling work "
      "A %.6e J, C %.6e J (input %.6e J); balance mono %.2e A %.2e C %.2e\n",
      worst / scale, ea.coupling_work_J, ec.coupling_work_J, em.external_work_J, em.balance_error(),
      ea.balance_error(), ec.balance_error());
}

namespace {

/// The first two numbers "X s" after `after` in `what` (0 where absent).
std::pair<double, double> two_steps_after(const std::string& what, const std::string& after) {
  std::pair<double, double> v{0.0, 0.0};
  auto at = what.find(after);
  if (at == std::string::npos) return v;
  at += after.size();
  for (double* x : {&v.first, &v.second}) {
    const auto start = what.find_first_of("0123456789", at);
    if (start == std::string::npos) break;
    std::size_t used = 0;
    *x = std::stod(what.substr(start), &used);
    at = start + used;
    if (what.compare(at, 2, " s") != 0) {  // not a step
      *x = 0.0;
      return v;
    }
  }
  return v;
}

}  // namespace

// A coordinator's step a hair above what a domain allows (a fixed step planned from the initial
// stable step, 1e-9 above the stable step as it has shrunk since; the README's by-hand recipe at
// --step-safety 1 stopped so at 3.56 ms) is refused, and the message prints the two steps as two
// different numbers, the imposed one the larger. Both were printed with 7 digits before, the same
// number twice ("imposed dt = 2.209825e-06 s, but this domain's stable step is 2.209825e-06 s").
TEST(CouplingHooks, RefusedImposedStepPrintsBothStepsApart) {
  auto m = bar_piece(0, 10, true);
  integration::Solver s(m, "body");
  s.initialize();
  const double allowed = s.dt_s();
  for (const double excess : {2e-9, 1e-6, 1.0}) {
    const double imposed = allowed * (1.0 + excess);
    try {
      s.impose_step(imposed);
      ADD_FAILURE() << "a step " << excess << " above the allowed one was taken";
    } catch (const NumericalError& e) {
      const std::string what = e.what();
      const auto [shown_imposed, shown_allowed] = two_steps_after(what, "imposed dt = ");
      EXPECT_GT(shown_imposed, shown_allowed) << what;
      EXPECT_NEAR(shown_imposed, imposed, 0.1 * excess * allowed) << what;
      EXPECT_NEAR(shown_allowed, allowed, 0.1 * excess * allowed) << what;
      EXPECT_NE(what.find("part 'bar'"), std::string::npos) << what;  // which element sets it
    }
  }
  // the same for a step committed at the start of an owner step (variable `layer` steps)
  const double stable = s.dt_stable_s();
  try {
    s.impose_committed_step(stable * (1.0 + 2e-9));
    ADD_FAILURE() << "a committed step above the stable one was taken";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    const auto [shown_committed, shown_stable] = two_steps_after(what, "the step ");
    EXPECT_GT(shown_committed, shown_stable) << what;
    EXPECT_NEAR(shown_stable, stable, 0.1 * 2e-9 * stable) << what;
  }
}
