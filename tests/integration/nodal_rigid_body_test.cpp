// Rigid bodies of extra nodes (model::RigidBody::nodes: LS-DYNA's nodal rigid body and extra
// nodes): nodes of deformable shells that follow one body, their rotations with it.
//  - a plate whose every node is in the body, spun about an in-plane axis: it turns as one
//    rigid plate, its shells unstrained (were the nodes' rotations left behind, the shells
//    would bend), the kinetic energy that of the body;
//  - a plate with a nodal rigid body over a strip of it, set spinning and translating with a
//    deformable remainder: linear and angular momentum kept (nodes, their rotations, the body),
//    the energy balance kept.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/network_vs_mono.h"
#include "tests/integration/run_helpers.h"

namespace crashlink {
namespace {

model::Model plate(double end_s) {
  return io::parse_scenario(
      R"(name: plate
controls: {end_time: )" +
          std::to_string(end_s) + R"(, history_interval: 0}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  plate: {material: steel, element: shell4, thickness: 2.0e-3, mesh: {generator: plate, origin: [-0.05, -0.05, 0], size: [0.1, 0.1], normal: z, divisions: [10, 10]}}
)",
      "plate.yaml");
}

TEST(NodalRigidBody, WholePlateTurnsAsOneWithoutStrain) {
  model::Model m = plate(2.0e-4);
  model::RigidBody rb;
  rb.name = "all";
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    rb.nodes.push_back(static_cast<std::int32_t>(i));
  rb.angular_velocity_rad_s = {50.0, 0.0, 0.0};  // about x, in the plate's plane
  rb.velocity_m_s = {1.0, 0.0, 0.5};
  m.rigid_bodies.push_back(rb);
  integration::Solver s(m);
  s.initialize();
  const double ke0 = [&] {
    s.begin_cycle();
    return s.energy().kinetic_J;
  }();
  double ie_max = 0.0;
  for (;;) {
    ie_max = std::max(ie_max, std::abs(s.energy().internal_J));
    if (s.finished()) break;
    s.end_cycle();
    s.begin_cycle();
  }
  const auto& b = s.rigid_bodies()[0];
  EXPECT_EQ(b.turning.size(), m.nodes.count()) << "every shell node turns with the body";
  // turned 50 rad/s about x (a principal axis of the square plate: a steady spin) until t^n
  EXPECT_NEAR(b.rotation[2][1], std::sin(50.0 * s.time_s()), 1e-9);
  std::printf("[measured] rigid plate of nodes: KE %.6e J, internal energy at most %.2e J\n", ke0,
              ie_max);
  EXPECT_LT(ie_max, 1e-12 * ke0) << "rigid motion strains nothing";
  EXPECT_NEAR(s.energy().kinetic_J, ke0, 1e-12 * ke0);
}

TEST(NodalRigidBody, StripOfAPlateKeepsMomentaAndEnergy) {
  model::Model m = plate(5.0e-4);
  model::RigidBody rb;
  rb.name = "strip";
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (m.nodes.x0[3 * i] < -0.035) rb.nodes.push_back(static_cast<std::int32_t>(i));  // 2 rows
  ASSERT_EQ(rb.nodes.size(), 22u);
  rb.angular_velocity_rad_s = {0.0, 40.0, 10.0};
  rb.velocity_m_s = {0.0, 0.0, 2.0};
  m.rigid_bodies.push_back(rb);
  integration::Solver s(m);
  s.initialize();
  const auto momenta = [&](Vec3& p, Vec3& L) {
    // nodes at v^n, their rotations (shell nodes' rotational inertia), and the body
    p = {};
    L = {};
    const auto& rigid = s.rigid_bodies()[0];
    std::vector<char> in_body(m.nodes.count(), 0);
    for (auto c : rigid.nodes) in_body[static_cast<std::size_t>(c)] = 1;
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      if (in_body[i]) continue;
      const Vec3 x{m.nodes.x0[3 * i] + s.displacement()[3 * i],
                   m.nodes.x0[3 * i + 1] + s.displacement()[3 * i + 1],
                   m.nodes.x0[3 * i + 2] + s.displacement()[3 * i + 2]};
      const Vec3 v = s.velocity_mid().size()
                         ? Vec3{s.velocity_mid()[3 * i], s.velocity_mid()[3 * i + 1],
                                s.velocity_mid()[3 * i + 2]}
                         : Vec3{};
      const Vec3 w{s.angular_velocity_mid()[3 * i], s.angular_velocity_mid()[3 * i + 1],
                   s.angular_velocity_mid()[3 * i + 2]};
      p = p + s.mass()[i] * v;
      L = L + s.mass()[i] * cross(x, v) + s.inertia()[i] * w;
    }
    p = p + rigid.mass_kg * rigid.velocity;
    L = L + cross(rigid.centre, rigid.mass_kg * rigid.velocity) + rigid.angular_momentum;
  };
  Vec3 p0, L0, p1, L1;
  s.begin_cycle();
  momenta(p0, L0);
  const double ke0 = s.energy().kinetic_J;
  double balance = 0.0;
  std::size_t cycles = 0;
  for (;;) {
    balance = std::max(balance, std::abs(s.energy().balance_J()));
    if (s.finished()) break;
    s.end_cycle();
    s.begin_cycle();
    ++cycles;
  }
  momenta(p1, L1);
  const auto& e = s.energy();
  std::printf(
      "[measured] nodal rigid strip: %zu cycles, internal %.3e J of KE0 %.3e J, "
      "|dp| %.2e of |p| %.3e, |dL| %.2e of |L| %.3e, balance at most %.2e J\n",
      cycles, e.internal_J, ke0, norm(p1 - p0), norm(p0), norm(L1 - L0), norm(L0), balance);
  EXPECT_GT(e.internal_J, 1e-3 * ke0) << "the free part of the plate flexes";
  EXPECT_LT(norm(p1 - p0), 1e-9 * norm(p0));
  // v^{n+1/2} and x^n are half a step apart: L to the order of that lag, not round-off
  EXPECT_LT(norm(L1 - L0), 1e-5 * norm(L0));
  EXPECT_LT(balance, 1e-3 * ke0);
}

/// A node probe on a body's node reads the body's acceleration there (an accelerometer tied by
/// a nodal rigid body): g under gravity. A node held by an SPC is refused in a body, and a node
/// in two bodies (a nodal body listed before a rigid part sharing its nodes) too.
TEST(NodalRigidBody, ProbeSpcAndSharedNodes) {
  model::Model m = plate(1.0e-4);
  m.controls.gravity_m_s2 = {0.0, 0.0, -9.81};
  model::RigidBody rb;
  rb.name = "sensor";
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (m.nodes.x0[3 * i] < -0.035) rb.nodes.push_back(static_cast<std::int32_t>(i));
  m.rigid_bodies.push_back(rb);
  m.probes.push_back({"tied", model::Probe::Kind::Node, rb.nodes[3]});
  integration::Solver s(m);
  s.initialize();
  s.begin_cycle();
  const auto a = s.probe(m.probes.back()).acceleration_m_s2;
  EXPECT_NEAR(a[2], -9.81, 1e-9);
  EXPECT_NEAR(a[0], 0.0, 1e-9);

  model::Model held = m;
  held.fixed[static_cast<std::size_t>(rb.nodes[0])] = model::kUx;
  std::string msg;
  try {
    integration::Solver h(held);
    h.initialize();
  } catch (const ModelError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("is held by a boundary condition"), std::string::npos) << msg;

  model::Model twice = m;
  model::RigidBody other;
  other.name = "other";
  other.nodes = {rb.nodes[0]};
  other.nodes.push_back(rb.nodes[1]);
  twice.rigid_bodies.push_back(other);
  msg.clear();
  try {
    integration::Solver t(twice);
    t.initialize();
  } catch (const ModelError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("belongs to rigid bodies 'sensor' and 'other'"), std::string::npos) << msg;
}

/// Across domains: a nodal rigid body inside one domain runs in split as in mono (to
/// round-off at their common step); one whose nodes' elements lie in two domains is refused
/// with the fix.
TEST(NodalRigidBody, InOneDomainSplitEqualsMonoAcrossTwoRefused) {
  const auto two = [](const std::string& nodes) {
    return io::parse_scenario(R"(name: two plates
controls: {end_time: 2.0e-4}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  left: {material: steel, element: shell4, thickness: 2.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.1, 0.1], normal: z, divisions: [10, 10]}}
  right: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0.1, 0, 0], size: [0.1, 0.1], normal: z, divisions: [20, 20]}, merge_nodes: true}
rigid_bodies:
  lump: {nodes: )" + nodes + R"(, velocity: [0.0, 0.0, 3.0], angular_velocity: [20.0, 0.0, 0.0]}
domains:
  coarse: {parts: [left]}
  fine: {parts: [right]}
)",
                              "two.yaml");
  };
  const model::Model inside = two("{part: left, box: {min: [-1, -1, -1], max: [0.02, 1, 1]}}");
  const auto r = testing::network_vs_mono(inside, 0);
  std::printf("[measured] nodal rigid body in one domain: split vs mono %.2e (max |u| %.3e m)\n",
              r.rel_diff, r.u_scale);
  EXPECT_GT(r.u_scale, 1e-5);
  EXPECT_LE(r.rel_diff, 1e-10);
  // nodes at x = 0.1 are the two plates' shared edge: elements of both domains use them
  const model::Model across = two("{part: left, box: {min: [0.09, -1, -1], max: [1, 1, 1]}}");
  std::string msg;
  try {
    cosim::LayerNetwork net(across);
  } catch (const ModelError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("rigid body 'lump' holds node"), std::string::npos) << msg;
  EXPECT_NE(msg.find("put the parts around its nodes in one domain"), std::string::npos) << msg;
}

}  // namespace
}  // namespace crashlink
