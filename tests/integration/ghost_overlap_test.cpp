// Overlap (docs/design.md §2.6): a `layer` fine domain computes the forces of its elements that
// touch no ghost node (J, whose motion the owner sends) before it waits for u_J, the rest after
// (Solver::end_cycle_interior_forces, cosim::LayerStepper Phase::Rim).
//   * The layer cut puts a fine domain's elements on J last in each part, so that the interior
//     span [0, interior_elements(p)) is the rest of the part up to whole batches (plate, block).
//   * Until their motion is applied, the ghosts' velocities (and positions) are NaN, so an element
//     wrongly taken for interior cannot use stale values quietly; end_cycle_compute() without the
//     ghosts' motion is refused; with it, u_J lands exactly and v_J = du / dt.
//   * Given after the interior forces or before the cycle, the same ghost motion gives the same
//     run to the bit (end_cycle_compute() computes the interior itself when nobody did).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/errors.h"
#include "solver/cosim/layer_domains.h"
#include "solver/integration/solver.h"
#include "tests/unit/partition/partition_models.h"

using namespace crashlink;

namespace {

bool touches_ghost(const model::Part& p, std::size_t e, const integration::Solver& s) {
  const auto k = static_cast<std::size_t>(model::nodes_per_element(p.kind));
  const auto& g = s.ghost_nodes();
  for (std::size_t j = 0; j < k; ++j)
    if (std::find(g.begin(), g.end(), p.connectivity[k * e + j]) != g.end()) return true;
  return false;
}

/// The solver of `d` that holds ghosts (the fine one of a two-domain cut), initialised.
integration::Solver& fine_solver(cosim::LayerDomains& d) {
  for (auto& s : d.solvers)
    if (!s->ghost_nodes().empty()) {
      s->initialize();
      return *s;
    }
  throw std::logic_error("no domain with ghosts");
}

/// A smooth motion for the ghosts at time t: their initial place plus 1e-5 m sin(2 pi 2 kHz t).
std::vector<double> ghost_motion(const integration::Solver& s, double t) {
  std::vector<double> u(3 * s.ghost_nodes().size());
  for (std::size_t k = 0; k < s.ghost_nodes().size(); ++k)
    for (std::size_t d = 0; d < 3; ++d)
      u[3 * k + d] = 1e-5 * std::sin(2.0 * M_PI * 2000.0 * t + static_cast<double>(k + d));
  return u;
}

}  // namespace

TEST(GhostOverlap, TheLayerCutPutsTheElementsOnJLast) {
  // block_on_floor: the floor's plate (4 x 4) moves into the block's domain for the contact; the
  // column on J (x = 0.5) is the last of every row of its elements in the global order.
  for (const auto& global :
       {crashlink::testing::plate_cut(), crashlink::testing::hex_block(),
        crashlink::testing::bar_two_sizes(), crashlink::testing::block_on_floor(),
        crashlink::testing::ball_on_ground()}) {
    auto d = cosim::build_layer_domains(global, "test");
    auto& s = fine_solver(d);
    const auto& m = s.model();
    std::size_t interior = 0, rim = 0;
    for (std::size_t p = 0; p < m.parts.size(); ++p) {
      const auto& part = m.parts[p];
      const std::size_t ne = part.element_count();
      std::size_t first_rim = ne;
      for (std::size_t e = 0; e < ne; ++e) {
        if (touches_ghost(part, e, s)) {
          first_rim = std::min(first_rim, e);
          ++rim;
        } else {
          EXPECT_EQ(first_rim, ne) << global.name << " part " << part.name << " element " << e
                                   << ": an element off J after one on J";
        }
      }
      const std::size_t span = s.interior_elements(p);
      EXPECT_LE(span, first_rim) << global.name << " part " << part.name;
      EXPECT_EQ(span % elements::kElementBatch == 0 || span == ne, true);
      EXPECT_EQ(span, first_rim == ne ? ne : first_rim / 8 * 8) << global.name << " " << part.name;
      interior += span;
    }
    EXPECT_GT(rim, 0u) << global.name;
    if (global.name == "block_on_floor") {  // 12 of the plate's 16 off J: one batch of 8
      const auto plate = std::find_if(m.parts.begin(), m.parts.end(),
                                      [](const model::Part& p) { return p.name == "plate"; });
      ASSERT_NE(plate, m.parts.end());
      EXPECT_EQ(s.interior_elements(static_cast<std::size_t>(plate - m.parts.begin())), 8u);
    }
    EXPECT_GT(interior, 0u) << global.name << ": nothing to overlap";
  }
}

TEST(GhostOverlap, GhostsAreUnknownUntilTheirMotionIsApplied) {
  const auto global = crashlink::testing::plate_cut();
  auto d = cosim::build_layer_domains(global, "test");
  auto& s = fine_solver(d);
  const auto& ghosts = s.ghost_nodes();
  s.begin_cycle();
  s.end_cycle_positions();
  for (const auto g : ghosts)
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_TRUE(std::isnan(s.velocity_mid()[3 * static_cast<std::size_t>(g) + c]));
  s.end_cycle_interior_forces();
  EXPECT_THROW(s.end_cycle_compute(), ModelError);

  auto d2 = cosim::build_layer_domains(global, "test");
  auto& s2 = fine_solver(d2);
  s2.begin_cycle();
  std::vector<double> u_before(3 * ghosts.size());
  for (std::size_t k = 0; k < ghosts.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c)
      u_before[3 * k + c] = s2.displacement()[3 * static_cast<std::size_t>(ghosts[k]) + c];
  const double dt = s2.dt_s();
  s2.end_cycle_positions();
  s2.end_cycle_interior_forces();
  const auto target = ghost_motion(s2, dt);
  s2.set_ghost_displacement(target.data());
  s2.end_cycle_compute();
  for (std::size_t k = 0; k < ghosts.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t i = 3 * static_cast<std::size_t>(ghosts[k]) + c;
      EXPECT_EQ(s2.displacement()[i], target[3 * k + c]);
      EXPECT_EQ(s2.velocity_mid()[i], (target[3 * k + c] - u_before[3 * k + c]) / dt);
    }
  s2.end_cycle_accelerations();
  for (double a : s2.acceleration()) ASSERT_TRUE(std::isfinite(a));
}

TEST(GhostOverlap, LateGhostMotionGivesTheSameRunToTheBit) {
  for (const auto& global : {crashlink::testing::plate_cut(), crashlink::testing::hex_block()}) {
    auto da = cosim::build_layer_domains(global, "test");
    auto db = cosim::build_layer_domains(global, "test");
    auto& a = fine_solver(da);
    auto& b = fine_solver(db);
    std::size_t moved = 0;
    for (int c = 0; c < 300; ++c) {
      const auto target = ghost_motion(a, a.time_s() + a.dt_s());
      a.begin_cycle();
      a.end_cycle_positions();
      a.end_cycle_interior_forces();
      a.set_ghost_displacement(target.data());  // as a fine domain whose u_J came late
      a.end_cycle_compute();
      a.end_cycle_accelerations();
      b.begin_cycle();
      b.set_ghost_displacement(target.data());  // before the cycle: no overlap
      b.end_cycle_forces();
      b.end_cycle_accelerations();
      for (std::size_t i = 0; i < a.displacement().size(); ++i) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.displacement()[i]),
                  std::bit_cast<std::uint64_t>(b.displacement()[i]))
            << global.name << " dof " << i << " cycle " << c;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.acceleration()[i]),
                  std::bit_cast<std::uint64_t>(b.acceleration()[i]))
            << global.name << " dof " << i << " cycle " << c;
        moved += a.displacement()[i] != 0.0;
      }
      ASSERT_EQ(a.energy().coupling_work_J, b.energy().coupling_work_J);
    }
    EXPECT_GT(moved, 0u);
  }
}
