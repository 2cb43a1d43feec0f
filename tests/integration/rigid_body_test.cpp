// Rigid body in free flight (issue 2 acceptance): linear and angular momentum kept to round-off;
// the body stays rigid; under gravity the centre follows c0 + v0 t + g t^2 / 2 exactly (central
// differences integrate a constant acceleration without error).
#include <gtest/gtest.h>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

namespace {

model::Model tumbling_box() {
  model::Model m;
  m.name = "tumbling box";
  m.materials.push_back({"rigid", materials::MaterialKind::Rigid, 2700.0, 70e9, 0.3, {}});
  model::Part p;
  p.name = "box";
  p.material = 0;
  model::generate_box(m, p, {{-0.05, -0.1, -0.15}, {0.1, 0.2, 0.3}, {2, 3, 4}});  // asymmetric top
  model::RigidBody rb;
  rb.name = "box";
  rb.parts = {0};
  rb.velocity_m_s = {1.0, -2.0, 3.0};
  rb.angular_velocity_rad_s = {20.0, -5.0, 12.0};  // not about a principal axis: it tumbles
  m.rigid_bodies.push_back(rb);
  m.probes.push_back({"centre", model::Probe::Kind::RigidBody, 0});
  m.controls.dt_max_s = 1e-5;
  m.controls.end_time_s = 0.1;  // 10^4 steps, several tumbling periods
  return m;
}

Vec3 angular_momentum_about_origin(const integration::RigidBodyState& b) {
  const Vec3 p = b.mass_kg * b.velocity;
  return mul(integration::spatial_inertia(b), b.omega) + cross(b.centre, p);
}

}  // namespace

TEST(RigidBody, FreeFlightKeepsMomentaToRoundOff) {
  auto m = tumbling_box();
  integration::Solver s(m);
  Vec3 p0{}, l0{};
  double scale_p = 0.0, scale_l = 0.0;
  double worst_p = 0.0, worst_l = 0.0, worst_orth = 0.0, worst_dist = 0.0;
  const std::size_t a = 0, b = m.nodes.count() - 1;  // two far-apart nodes
  auto dist = [&](const integration::Solver& sv) {
    Vec3 xa{}, xb{};
    for (std::size_t d = 0; d < 3; ++d) {
      xa[d] = m.nodes.x0[3 * a + d] + sv.displacement()[3 * a + d];
      xb[d] = m.nodes.x0[3 * b + d] + sv.displacement()[3 * b + d];
    }
    return norm(xa - xb);
  };
  double d0 = 0.0;
  run(s, [&](const integration::Solver& sv) {
    const auto& body = sv.rigid_bodies()[0];
    const Vec3 p = body.mass_kg * body.velocity;
    const Vec3 l = angular_momentum_about_origin(body);
    if (sv.cycle() == 0) {
      p0 = p;
      l0 = l;
      scale_p = norm(p0);
      scale_l = norm(l0);
      d0 = dist(sv);
    }
    worst_p = std::max(worst_p, norm(p - p0) / scale_p);
    worst_l = std::max(worst_l, norm(l - l0) / scale_l);
    const Mat3 rtr = mul(transpose(body.rotation), body.rotation);
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j)
        worst_orth = std::max(worst_orth, std::abs(rtr[i][j] - (i == j ? 1.0 : 0.0)));
    worst_dist = std::max(worst_dist, std::abs(dist(sv) - d0) / d0);
  });
  // Round-off over 10^4 steps: ~1e4 * 1e-16 accumulated, bound 1e-11.
  EXPECT_LT(worst_p, 1e-11);
  EXPECT_LT(worst_l, 1e-11);
  EXPECT_LT(worst_orth, 1e-11);
  EXPECT_LT(worst_dist, 1e-11);
  EXPECT_GE(s.cycle(), 10000);
}

TEST(RigidBody, FallsUnderGravityExactly) {
  auto m = tumbling_box();
  m.rigid_bodies[0].angular_velocity_rad_s = {0.0, 0.0, 0.0};
  m.controls.gravity_m_s2 = {0.0, 0.0, -9.81};
  integration::Solver s(m);
  double worst = 0.0;
  run(s, [&](const integration::Solver& sv) {
    const double t = sv.time_s();
    const auto pr = sv.probe(sv.model().probes[0]);
    const Vec3 expected{1.0 * t, -2.0 * t, 3.0 * t - 0.5 * 9.81 * t * t};
    worst = std::max(worst, norm(pr.displacement_m - expected));
  });
  EXPECT_LT(worst, 1e-12);  // metres; round-off of 10^4 additions of ~1e-5 m
  // Energy: the balance includes the work of gravity (bound: round-off relative to 1e-10).
  EXPECT_LT(std::abs(s.energy().balance_error()), 1e-10);
}
