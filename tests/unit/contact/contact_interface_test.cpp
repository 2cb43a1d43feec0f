// ContactInterface on small hand-made configurations (no time integration): the thickness
// offsets, the exact-touching threshold, the SOFT=0 stiffness value, momentum balance of the
// distributed forces, continuity across segment edges, and the friction cone.
#include "solver/contact/contact_interface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "solver/contact/friction.h"
#include "solver/core/state_archive.h"
#include "solver/model/mesh_generators.h"

using namespace crashlink;
using namespace crashlink::contact;

namespace {

constexpr double kT = 0.01;  // plate thickness [m]

/// A 4 x 4 steel shell plate (1 m x 1 m, z = 0, normal +z) and one steel hex (0.2 m) above it
/// whose bottom face is at z = kT/2 (touching). Slave: the hex's nodes; master: the plate.
struct Scene {
  model::Model m;
  std::vector<double> mass;
  std::vector<std::int32_t> hex_nodes;
};

/// A part of material 0 (steel) with this name and shell thickness (0 for solids).
model::Part steel_part(const std::string& name, double thickness_m) {
  model::Part p;
  p.name = name;
  p.material = 0;
  p.thickness_m = thickness_m;
  return p;
}

void add_steel(model::Model& m) {
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
}

Scene make_scene() {
  Scene s;
  add_steel(s.m);
  model::generate_plate(s.m, steel_part("plate", kT),
                        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {4, 4}, 0.0});
  const std::size_t before = s.m.nodes.count();
  const model::Part hex = steel_part("block", 0.0);
  model::generate_box(s.m, hex, {{0.3, 0.3, 0.5 * kT}, {0.2, 0.2, 0.2}, {1, 1, 1}});
  for (std::size_t i = before; i < s.m.nodes.count(); ++i)
    s.hex_nodes.push_back(static_cast<std::int32_t>(i));
  s.mass.assign(s.m.nodes.count(), 1.0);
  model::Contact c;
  c.name = "block-plate";
  c.kind = model::ContactKind::NodeToSurface;  // one pass, segment stiffness alone (SOFT=0)
  c.soft = false;
  c.slave_nodes = s.hex_nodes;
  c.master_parts = {0};
  s.m.contacts.push_back(c);
  return s;
}

/// Forces with the block's nodes shifted by dz (and dx) from the reference.
ContactStep forces_at(const Scene& s, double dz, std::vector<double>& f, double dx = 0.0) {
  std::vector<double> x = s.m.nodes.x0, v(x.size(), 0.0);
  for (auto i : s.hex_nodes) {
    x[3 * static_cast<std::size_t>(i)] += dx;
    x[3 * static_cast<std::size_t>(i) + 2] += dz;
  }
  f.assign(x.size(), 0.0);
  ContactInterface ci(s.m, s.m.contacts[0], s.mass.data());
  return ci.compute(x.data(), v.data(), 0.0, f.data());
}

double max_abs(const std::vector<double>& f) {
  double m = 0.0;
  for (double v : f) m = std::max(m, std::fabs(v));
  return m;
}

}  // namespace

TEST(ContactInterface, NoForceBeyondTheGapOrExactlyTouching) {
  const Scene s = make_scene();
  std::vector<double> f;
  for (double dz : {1e-3, 1e-6, 0.0, 0.5 * kT * 1e-12}) {  // apart, barely apart, touching
    const auto r = forces_at(s, dz, f);
    EXPECT_EQ(r.active_pairs, 0) << "dz = " << dz;
    EXPECT_EQ(max_abs(f), 0.0) << "dz = " << dz;  // exactly zero: g = h - d is not > 0
  }
  // Within round-off below the touching position: at most k * (a few ulps of h): < 1e-6 N.
  const auto r = forces_at(s, -0.5 * kT * 1e-15, f);
  EXPECT_LT(max_abs(f), 1e-6);
  (void)r;
}

TEST(ContactInterface, StiffnessIsLsDynaSoft0AndForcesBalance) {
  const Scene s = make_scene();
  std::vector<double> f;
  const double g = 1e-5;
  const auto r = forces_at(s, -g, f);
  EXPECT_EQ(r.active_pairs, 4);  // the 4 bottom nodes
  // k = s K A / max diagonal (Hallquist, LS-DYNA Theory Manual, penalty method), plate
  // element 0.25 m square: A = 0.0625, diagonal 0.25 sqrt 2, K = E / (3 (1 - 2 nu)).
  const double K = 210e9 / (3.0 * (1.0 - 0.6));
  const double k = 0.1 * K * 0.0625 / (0.25 * std::sqrt(2.0));
  EXPECT_NEAR(r.resultant_N[2], 4.0 * k * g, 1e-9 * 4.0 * k * g);  // round-off only
  EXPECT_NEAR(r.resultant_N[0], 0.0, 1e-6);
  double sum[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < f.size(); ++i) sum[i % 3] += f[i];
  for (double v : sum) EXPECT_LE(std::fabs(v), 1e-12 * 4.0 * k * g);  // momentum: round-off
  // Step bound: the spring's critical step 2 sqrt(m_eff / k) with the contact's element
  // masses: a block corner carries rho V / 8, a plate segment's mean node rho t A / 4 times the
  // elements around it (interior node 4, edge 2, corner 1): the block's bottom nodes lie over
  // interior nodes' segments. At the start it is the least of every pair that may ever touch.
  const double m_corner = 7850.0 * 0.008 / 8.0;
  const double m_share = 7850.0 * kT * 0.0625 / 4.0;
  double least = std::numeric_limits<double>::infinity();
  for (double seg_mean :
       {m_share * (1 + 2 + 2 + 4) / 4.0, m_share * (2 + 4 + 4 + 4) / 4.0, m_share * 4.0})
    least = std::min(least, 2.0 * std::sqrt(1.0 / (1.0 / m_corner + 1.0 / seg_mean) / k));
  EXPECT_LE(r.dt_stable_s, least * (1.0 + 1e-12));
  ContactInterface ci(s.m, s.m.contacts[0], s.mass.data());
  std::vector<double> x = s.m.nodes.x0, v(x.size(), 0.0), f2(x.size(), 0.0);
  for (auto i : s.hex_nodes) x[3 * static_cast<std::size_t>(i) + 2] -= g;
  ci.compute(x.data(), v.data(), 0.0, f2.data());
  const auto later = ci.compute(x.data(), v.data(), 1e-9, f2.data());  // the candidates' own
  EXPECT_GE(later.dt_stable_s, r.dt_stable_s);
  EXPECT_LE(later.dt_stable_s, 2.0 * std::sqrt(m_corner / k) * (1.0 + 1e-12));
}

TEST(ContactInterface, ForceContinuousAcrossSegmentEdges) {
  // The block slides along x so that its nodes cross the plate's element edges (x = 0.5) and
  // vertices: the resultant and each master node's force change by O(dx) only.
  const Scene s = make_scene();
  std::vector<double> f0, f1;
  const double g = 1e-5;
  for (double edge : {0.5 - 0.3, 0.5 - 0.5}) {  // bottom node x = 0.3 + dx crosses x = 0.5
    const double eps = 1e-9;
    forces_at(s, -g, f0, edge - eps);
    forces_at(s, -g, f1, edge + eps);
    double diff = 0.0;
    for (std::size_t i = 0; i < f0.size(); ++i) diff = std::max(diff, std::fabs(f0[i] - f1[i]));
    EXPECT_LT(diff, 1e-6 * max_abs(f0)) << "edge shift " << edge;
  }
}

TEST(ContactInterface, ShellSlaveUsesBothOffsets) {
  // A second plate (t2 = 4 mm) above the first: contact at distance (t + t2) / 2.
  model::Model m;
  add_steel(m);
  const model::Part a = steel_part("lower", kT);
  model::generate_plate(m, a, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {4, 4}, 0.0});
  const std::size_t before = m.nodes.count();
  model::Part b = a;
  b.name = "upper";
  b.thickness_m = 0.004;
  const double h = 0.5 * (kT + 0.004);
  model::generate_plate(m, b, {{0.1, 0.1, h}, {0.3, 0, 0}, {0, 0.3, 0}, {1, 1}, 0.0});
  model::Contact c;
  c.name = "plates";
  c.kind = model::ContactKind::NodeToSurface;
  c.master_parts = {0};
  for (std::size_t i = before; i < m.nodes.count(); ++i)
    c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  std::vector<double> mass(m.nodes.count(), 1.0), v(3 * m.nodes.count(), 0.0), f(v.size(), 0.0);
  ContactInterface ci(m, c, mass.data());
  std::vector<double> x = m.nodes.x0;
  EXPECT_EQ(ci.compute(x.data(), v.data(), 0.0, f.data()).active_pairs, 0);  // touching
  for (std::size_t i = before; i < m.nodes.count(); ++i) x[3 * i + 2] -= 1e-4;
  EXPECT_EQ(ci.compute(x.data(), v.data(), 0.0, f.data()).active_pairs, 4);
  // From below (the other side of the two-sided shell) too; a fresh interface, because one in
  // contact keeps its side (a node pushed past the mid-surface is pushed back, not through).
  for (std::size_t i = before; i < m.nodes.count(); ++i) x[3 * i + 2] = -h + 1e-4;
  std::fill(f.begin(), f.end(), 0.0);
  ContactInterface fresh(m, c, mass.data());
  const auto r = fresh.compute(x.data(), v.data(), 0.0, f.data());
  EXPECT_EQ(r.active_pairs, 4);
  EXPECT_LT(r.resultant_N[2], 0.0);  // pushed down, away from the lower plate
}

TEST(Friction, ElasticPredictorThenCone) {
  const FrictionLaw law{0.5, 0.3, 10.0};
  const double n[3] = {0, 0, 1}, v[3] = {1e-3, 0, 0};
  double ft[3] = {0, 0, 0};
  friction_update(law, n, v, 1e6, 1e-6, 100.0, ft);  // stick: -k v dt = -1e-3 N
  EXPECT_NEAR(ft[0], -1e-3, 1e-15);
  const double fast[3] = {2.0, 0, 0};
  friction_update(law, n, fast, 1e9, 1e-3, 100.0, ft);  // slip: mu(2 m/s) F_n
  const double mu = 0.3 + 0.2 * std::exp(-20.0);
  EXPECT_NEAR(ft[0], -mu * 100.0, 1e-12);
  // History carried onto a tilted tangent plane keeps its magnitude.
  const double n2[3] = {std::sqrt(0.5), 0, std::sqrt(0.5)}, zero[3] = {0, 0, 0};
  friction_update(law, n2, zero, 1e9, 1e-3, 1000.0, ft);
  EXPECT_NEAR(std::sqrt(ft[0] * ft[0] + ft[2] * ft[2]), mu * 100.0, 1e-12);
  EXPECT_NEAR(ft[0] * n2[0] + ft[2] * n2[2], 0.0, 1e-12);
}

// Sleeping slave nodes (contact_interface.cpp, header): a node out of reach of all its candidates
// skips the tests until the travel bound says it may have come within reach. A block of 7 x 7 x 4
// slave nodes, tilted, falls at 2 m/s and slides at 0.5 m/s onto a 10 x 10 plate over 200 steps
// of 1 ms. Interface A keeps its state; interface B is saved and restored every cycle, which wakes
// every node (nothing sleeps in B). The forces must be the same bits every cycle, and A must have
// skipped tests. A wake-up bound too late (e.g. G instead of G / 2) makes nodes sleep through
// their first contact and fails the equality.
TEST(ContactInterface, SleepingNodesGiveTheSameForces) {
  model::Model m;
  add_steel(m);
  model::generate_plate(m, steel_part("plate", kT),
                        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 10}, 0.0});
  const std::size_t first = m.nodes.count();
  model::generate_box(m, steel_part("block", 0.0), {{0.2, 0.2, 0.02}, {0.6, 0.6, 0.3}, {6, 6, 3}});
  model::Contact c;
  c.name = "block-plate";
  for (std::size_t i = first; i < m.nodes.count(); ++i) {
    c.slave_nodes.push_back(static_cast<std::int32_t>(i));
    m.nodes.x0[3 * i + 2] += 0.15 * (m.nodes.x0[3 * i] - 0.2);  // tilted: they arrive in turn
  }
  c.master_parts = {0};
  m.contacts.push_back(c);
  const std::vector<double> mass(m.nodes.count(), 1.0);
  ContactInterface a(m, m.contacts[0], mass.data()), b(m, m.contacts[0], mass.data());
  std::vector<double> x = m.nodes.x0, v(x.size(), 0.0);
  for (std::size_t i = first; i < m.nodes.count(); ++i) {
    v[3 * i] = 0.5;
    v[3 * i + 2] = -2.0;
  }
  const std::string path =
      (std::filesystem::temp_directory_path() / "crashlink_contact_sleep_test.state").string();
  const double dt = 1e-3;
  std::int64_t contacts = 0;
  for (int n = 0; n < 200; ++n) {
    for (std::size_t k = 0; k < x.size(); ++k) x[k] += dt * v[k];
    core::StateWriter w;
    b.save_state(w, "c.");
    w.save(path);
    b.restore_state(core::StateReader(path), "c.");
    std::vector<double> fa(x.size(), 0.0), fb(x.size(), 0.0);
    const auto sa = a.compute(x.data(), v.data(), dt, fa.data());
    const auto sb = b.compute(x.data(), v.data(), dt, fb.data());
    ASSERT_EQ(sa.active_pairs, sb.active_pairs) << "cycle " << n;
    for (std::size_t k = 0; k < x.size(); ++k) ASSERT_EQ(fa[k], fb[k]) << "cycle " << n;
    contacts += sa.active_pairs;
  }
  std::filesystem::remove(path);
  EXPECT_GT(contacts, 500);                // the block did land
  EXPECT_GT(a.slept_node_cycles(), 2000);  // and A skipped tests
  EXPECT_EQ(b.slept_node_cycles(), 0);
  std::printf("[measured] sleeping: %lld node tests skipped of %d, %lld contact pairs\n",
              static_cast<long long>(a.slept_node_cycles()),
              200 * static_cast<int>(m.contacts[0].slave_nodes.size()),
              static_cast<long long>(contacts));
}

TEST(ContactInterface, SingleSurfaceSeesATriangleOverAQuad) {
  // One shell part: a 10 mm quad at z = 0 and a triangle 0.6 mm above it (t = 1 mm, so the
  // mid-surfaces must stay 1 mm apart). Single-surface: the triangle's three nodes press on the
  // quad (none of the quad's segments is the triangle's own or a neighbour). A triangle's
  // repeated node once made segment 0 everybody's "own" segment: no pair at all.
  model::Model m;
  add_steel(m);
  const double z = 0.0006;
  m.nodes.x0 = {0, 0,     0,     0.01, 0,     0,     0.01, 0.01,  0,     0, 0.01,
                0, 0.002, 0.002, z,    0.008, 0.002, z,    0.005, 0.008, z};
  m.nodes.id = {1, 2, 3, 4, 5, 6, 7};
  model::Part p = steel_part("folded", 0.001);
  p.kind = model::ElementKind::Shell4;
  p.connectivity = {0, 1, 2, 3, 4, 5, 6, 6};
  p.element_id = {1, 2};
  m.parts.push_back(p);
  m.fixed.assign(m.nodes.count(), 0);
  model::Contact c;
  c.name = "self";
  c.kind = model::ContactKind::SingleSurface;
  c.master_parts = {0};
  std::vector<double> mass(m.nodes.count(), 1e-4), v(3 * m.nodes.count(), 0.0), f(v.size(), 0.0);
  ContactInterface ci(m, c, mass.data());
  const auto r = ci.compute(m.nodes.x0.data(), v.data(), 0.0, f.data());
  EXPECT_EQ(r.active_pairs, 3);  // the triangle's nodes; the quad's lie outside the triangle
  for (std::size_t i = 4; i < 7; ++i) EXPECT_GT(f[3 * i + 2], 0.0) << "node " << i;
}
