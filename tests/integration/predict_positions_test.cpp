// Solver::predict_next_positions: a coarse `layer` daemon sends u_J(t^{n+2}) computed before its
// nodal passes (cosim::LayerStepper). The values must be the passes' own, to the bit, whatever
// loads, held dofs and steps a node has: on a clamped shell strip (rotations) under gravity
// (external loads), with coupling forces and moments on some nodes and not others, and a step
// that changes every cycle, the prediction made at t^{n+1} equals u^{n+2} and omega^{n+3/2} as
// the next cycle computes them, on every node, for 300 cycles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "solver/integration/solver.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

model::Model loaded_strip() {
  auto m = shell_cantilever(0.2, 0.04, 1e-3, 10, 2, steel());
  m.controls.gravity_m_s2 = {0.0, 0.0, -9.81e3};  // strong enough to move it in 300 cycles
  m.controls.end_time_s = 1.0;
  // the arbitrary coupling loads below balance nothing: the energy guard is not under test
  m.controls.energy_tolerance = 1e6;
  // a few held dofs off the clamp too: z and the rotation about x at the tip's first node
  const auto tip = nodes_where(m, [](const Vec3& x) { return x[0] > 0.2 - 1e-9; });
  fix(m, {tip.front()}, model::kUz | model::kRx);
  return m;
}

}  // namespace

TEST(PredictNextPositions, EqualsTheNextCyclesPassesToTheBit) {
  const auto m = loaded_strip();
  integration::Solver s(m, "coarse");
  s.initialize();
  const std::size_t n = m.nodes.count();
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  std::vector<double> u_pred(3 * n), w_pred(3 * n);
  bool have = false;
  std::size_t moved = 0;  // dofs whose predicted u changed: the test is not about zeros
  for (int c = 0; c < 300; ++c) {
    s.begin_cycle();
    if (have) {
      for (std::size_t k = 0; k < 3 * n; ++k)
        ASSERT_EQ(s.angular_velocity_mid()[k], w_pred[k]) << "omega, dof " << k << ", cycle " << c;
    }
    s.end_cycle_positions();
    if (have) {
      for (std::size_t k = 0; k < 3 * n; ++k)
        ASSERT_EQ(s.displacement()[k], u_pred[k]) << "u, dof " << k << ", cycle " << c;
    }
    s.end_cycle_compute();
    // coupling loads on every other node (a layer's J): forces and moments that vary in time
    for (std::size_t i = 0; i < n; i += 2) {
      const double phase = 0.1 * c + static_cast<double>(i);
      s.add_coupling_force(i, {3.0 * std::sin(phase), -2.0 * std::cos(phase), 5.0});
      s.add_coupling_moment(i, {1e-3 * std::cos(phase), 2e-3, -1e-3 * std::sin(phase)});
    }
    const double dt_next = s.dt_s() * (0.7 + 0.05 * (c % 4));  // a different step each cycle
    const std::vector<double> u_before = s.displacement();
    ASSERT_TRUE(s.predict_next_positions(all, dt_next, u_pred.data(), w_pred.data()));
    for (std::size_t k = 0; k < 3 * n; ++k) moved += u_pred[k] != u_before[k];
    have = true;
    s.end_cycle_accelerations();
    s.impose_step(dt_next);
  }
  EXPECT_GT(moved, 300u * n);  // most free dofs move every cycle
}

TEST(PredictNextPositions, RefusesNodesThatMoveOtherwise) {
  auto m = loaded_strip();
  const auto tip = nodes_where(m, [](const Vec3& x) { return x[0] > 0.2 - 1e-9; });
  const auto prescribed = static_cast<std::size_t>(tip.back());
  m.prescribed_velocities.push_back(
      {"pull", {tip.back()}, 2, model::Curve{{0.0, 1.0}, {0.1, 0.1}}});
  const std::size_t ghost = 5;
  integration::Solver s(m, "coarse");
  s.set_ghost_nodes({static_cast<std::int32_t>(ghost)});
  s.initialize();
  s.begin_cycle();
  s.set_ghost_displacement(std::vector<double>(3, 0.0).data());
  s.end_cycle_positions();
  s.end_cycle_compute();
  std::vector<double> u(3, -1.0);
  EXPECT_FALSE(s.predict_next_positions({prescribed}, s.dt_s(), u.data(), nullptr));
  EXPECT_FALSE(s.predict_next_positions({ghost}, s.dt_s(), u.data(), nullptr));
  EXPECT_FALSE(s.predict_next_positions({1, m.nodes.count()}, s.dt_s(), u.data(), nullptr));
  EXPECT_EQ(u[0], -1.0);  // nothing written when refused
  // a step above what the stable step allows: impose_step() would refuse it, so does this
  EXPECT_FALSE(s.predict_next_positions({1}, 10.0 * s.dt_s(), u.data(), nullptr));
  // the other nodes of a model with prescribed velocities take begin_cycle's other path
  // (advance_velocity, then the held dofs, then the prescribed values): the same bits
  const double dt_next = 0.5 * s.dt_s();
  std::vector<double> w(3, 0.0);
  ASSERT_TRUE(s.predict_next_positions({1}, dt_next, u.data(), w.data()));
  s.end_cycle_accelerations();
  s.impose_step(dt_next);
  s.begin_cycle();
  for (std::size_t d = 0; d < 3; ++d) EXPECT_EQ(s.angular_velocity_mid()[3 + d], w[d]) << d;
  s.set_ghost_displacement(std::vector<double>(3, 0.0).data());
  s.end_cycle_positions();
  for (std::size_t d = 0; d < 3; ++d) EXPECT_EQ(s.displacement()[3 + d], u[d]) << d;
  EXPECT_NE(u[2], 0.0);  // gravity moved it
}
