// A block of hexahedra slides on a fixed shell plate under gravity with an initial speed and
// mu_s = mu_d = mu: Coulomb friction decelerates it at mu g (a = F_t / m = mu m g / m). The
// deceleration is the least-squares slope of the block's mean velocity over a window after the
// landing transient; 2 % tolerance covers the penalty bounce (the normal force oscillates about
// m g; its mean is m g) and the block's elastic vibrations. A soft rubber-like material keeps
// the run short (about 2000 steps).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

TEST(ContactFriction, SlidingBlockDeceleratesAtMuG) {
  constexpr double kMu = 0.3, kG = 9.81, kV0 = 1.0, kT = 0.002;
  model::Model m;
  m.name = "sliding block";
  m.materials.push_back({"soft", materials::MaterialKind::Elastic, 1000.0, 1e7, 0.3, {}});
  model::Part plate;
  plate.name = "floor";
  plate.material = 0;
  plate.thickness_m = kT;
  model::generate_plate(m, plate, {{-0.05, -0.1, 0.0}, {0.6, 0, 0}, {0, 0.2, 0}, {12, 4}, 0.0});
  const std::size_t n_plate = m.nodes.count();
  model::Part block;
  block.name = "block";
  block.material = 0;
  model::generate_box(m, block, {{0.0, -0.02, 0.5 * kT}, {0.04, 0.04, 0.02}, {2, 2, 1}});
  m.fixed.assign(m.nodes.count(), 0);
  std::vector<std::int32_t> floor_nodes, block_nodes;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    (i < n_plate ? floor_nodes : block_nodes).push_back(static_cast<std::int32_t>(i));
  fix(m, floor_nodes, 63);
  m.initial_velocities.push_back({block_nodes, {kV0, 0.0, 0.0}});
  model::Contact c;
  c.name = "block-floor";
  c.slave_nodes = block_nodes;
  c.master_parts = {0};
  c.static_friction = kMu;
  c.dynamic_friction = kMu;
  m.contacts.push_back(c);
  m.controls.gravity_m_s2 = {0.0, 0.0, -kG};
  m.controls.end_time_s = 0.2;
  integration::Solver s(m);
  std::vector<double> t, v;
  run(s, [&](const integration::Solver& sv) {
    double p = 0.0, mass = 0.0;
    for (auto i : block_nodes) {
      const auto k = static_cast<std::size_t>(i);
      p += sv.mass()[k] * sv.node_velocity(k)[0];
      mass += sv.mass()[k];
    }
    t.push_back(sv.time_s());
    v.push_back(p / mass);
  });
  // Least-squares slope of v(t) over [0.02, 0.2] s.
  double st = 0, sv = 0, stt = 0, stv = 0, n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 0.02) continue;
    st += t[i], sv += v[i], stt += t[i] * t[i], stv += t[i] * v[i], n += 1;
  }
  const double slope = (n * stv - st * sv) / (n * stt - st * st);
  const double expected = -kMu * kG;
  EXPECT_GT(v.back(), 0.2);  // still sliding at the end (the law holds only while sliding)
  EXPECT_NEAR(slope, expected, 0.02 * std::fabs(expected))
      << "deceleration " << -slope << " m/s^2, mu g = " << -expected;
  std::printf("sliding block: deceleration %.5f m/s^2, mu g = %.5f (ratio %.5f), %zu cycles\n",
              -slope, -expected, slope / expected, t.size());
}
