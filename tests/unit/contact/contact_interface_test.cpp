// ContactInterface on small hand-made configurations (no time integration): the thickness
// offsets, the exact-touching threshold, the SOFT=0 stiffness value, momentum balance of the
// distributed forces, continuity across segment edges, and the friction cone.
#include "solver/contact/contact_interface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/state_archive.h"
#include "solver/contact/friction.h"
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

TEST(ContactInterface, SingleSurfaceNodeBetweenTwoWallsKeepsItsEnergy) {
  // Issue 21 (the fine-mesh tube's folds): a shell node squeezed between two walls of the same
  // single-surface contact whose mid-surfaces are closer than 2 h (h = t here), both normals +z,
  // so the node lies on the + side of the lower wall and on the - side of the upper one. Walls
  // A (z = 0) and B (z = 2.9 mm) fixed, 40 mm squares; M a free 10 mm square in between, its
  // nodes point masses released at rest at z = 1.42 mm: in contact with A (g = 0.08 mm), within
  // h of B too (g = 0.02 mm). A's spring pushes M up; past z = 1.45 mm B is the nearer wall and
  // pushes it back: M rattles in the V-shaped well 1/2 k (h - min(d_A, d_B))^2, frictionless,
  // so kinetic + contact potential is conserved up to the central-difference step's error, and
  // the booked contact energy follows the potential. The side a node had on A was once carried
  // to B when the nearest wall changed: g jumped from 0.05 mm to h + 1.45 mm, the spring shot
  // M through B (E grew ~1000-fold).
  model::Model m;
  add_steel(m);
  const double t = 1.5e-3, gap = 2.9e-3, z0 = 1.42e-3;
  model::generate_plate(m, steel_part("A", t),
                        {{-0.02, -0.02, 0.0}, {0.04, 0, 0}, {0, 0.04, 0}, {1, 1}, 0.0});
  model::generate_plate(m, steel_part("B", t),
                        {{-0.02, -0.02, gap}, {0.04, 0, 0}, {0, 0.04, 0}, {1, 1}, 0.0});
  model::generate_plate(m, steel_part("M", t),
                        {{-0.005, -0.005, z0}, {0.01, 0, 0}, {0, 0.01, 0}, {1, 1}, 0.0});
  for (auto& p : m.parts) p.kind = model::ElementKind::Shell4;
  m.fixed.assign(m.nodes.count(), 0);
  model::Contact c;
  c.name = "self";
  c.kind = model::ContactKind::SingleSurface;
  c.soft = false;  // segment stiffness alone: no dt0 needed
  c.master_parts = {0, 1, 2};
  const std::size_t n = m.nodes.count();
  const double mass_M = 7850.0 * t * 1e-4 / 4.0;  // rho t A / 4 [kg]
  std::vector<double> mass(n, mass_M), x = m.nodes.x0, v(3 * n, 0.0), f(3 * n, 0.0);
  ContactInterface ci(m, c, mass.data());
  const auto first = ci.compute(x.data(), v.data(), 0.0, f.data());
  ASSERT_EQ(first.active_pairs, 4);  // M's nodes on A
  // k of A's segment (0.1 K A / diagonal) on a node of mass_M: dt = 0.05 / omega
  const double K = 210e9 / (3.0 * (1.0 - 0.6));
  const double k = 0.1 * K * 0.0016 / (0.04 * std::sqrt(2.0));
  const double dt = 0.05 * std::sqrt(mass_M / k);
  const double E0 = first.potential_J;
  ASSERT_GT(E0, 0.0);
  double worst = 0.0, booked_worst = 0.0, z_min = 1.0, z_max = 0.0;
  std::vector<double> v_old(3 * n, 0.0);
  ContactStep r = first;
  for (int step = 0; step < 4000; ++step) {
    // central difference on M's nodes (8..11), A and B held
    v_old = v;
    for (std::size_t i = 8; i < 12; ++i)
      for (std::size_t a = 0; a < 3; ++a) {
        v[3 * i + a] += dt * f[3 * i + a] / mass_M;
        x[3 * i + a] += dt * v[3 * i + a];
      }
    std::fill(f.begin(), f.end(), 0.0);
    r = ci.compute(x.data(), v.data(), dt, f.data());
    double ke = 0.0;  // at t^n: the mean of the two half-step velocities
    for (std::size_t i = 8; i < 12; ++i) {
      for (std::size_t a = 0; a < 3; ++a) {
        const double vm = 0.5 * (v[3 * i + a] + v_old[3 * i + a]);
        ke += 0.5 * mass_M * vm * vm;
      }
      z_min = std::min(z_min, x[3 * i + 2]);
      z_max = std::max(z_max, x[3 * i + 2]);
    }
    // ke lags the potential by half a step: compare at the previous step's potential too
    worst = std::max(worst, std::fabs(ke + r.potential_J - E0) / E0);
    booked_worst = std::max(booked_worst, std::fabs(r.energy_J - (r.potential_J - E0)) / E0);
  }
  EXPECT_LT(worst, 0.02) << "kinetic + contact potential drifts from E0 = " << E0 << " J";
  EXPECT_LT(booked_worst, 0.02) << "the booked contact energy leaves the potential";
  EXPECT_GT(z_min, 1.38e-3);  // M stays in the well between the walls
  EXPECT_LT(z_max, 1.52e-3);
}

TEST(ContactInterface, SingleSurfaceSqueezedNodeReturnsItsEnergy) {
  // Issue 21, the fine-mesh tube's corner nodes: a fold's layers close on a node from both sides
  // (each within h of it), then open again. Walls A (below, normal +z) and B (above, normal -z,
  // the fold's other layer) are driven symmetrically: their mid-surfaces 3.2 mm apart (> 2 h,
  // h = t = 1.5 mm), closing to 2.9 mm and back to 3.2 mm along a cosine over 20 us (15 m/s at
  // most, as the tube); M's nodes (point masses, released at rest 0.01 mm above the middle) float
  // in between. The contact is frictionless: once open again it must have given back what it
  // stored, its booked energy ~0. With the nearest wall alone pushing, the node's force flipped
  // from one wall's to the other's at every crossing of the middle (the V-shaped potential 1/2 k (h
  // - min(d_A, d_B))^2): the central-difference step created energy at each of those switches.
  model::Model m;
  add_steel(m);
  const double t = 1.5e-3, g_open = 3.2e-3, g_closed = 2.9e-3;
  model::generate_plate(m, steel_part("A", t),
                        {{-0.02, -0.02, -0.5 * g_open}, {0.04, 0, 0}, {0, 0.04, 0}, {1, 1}, 0.0});
  model::generate_plate(m, steel_part("B", t),  // edge2 along -y: normal -z
                        {{-0.02, 0.02, 0.5 * g_open}, {0.04, 0, 0}, {0, -0.04, 0}, {1, 1}, 0.0});
  model::generate_plate(m, steel_part("M", t),
                        {{-0.005, -0.005, 1e-5}, {0.01, 0, 0}, {0, 0.01, 0}, {1, 1}, 0.0});
  for (auto& p : m.parts) p.kind = model::ElementKind::Shell4;
  m.fixed.assign(m.nodes.count(), 0);
  model::Contact c;
  c.name = "self";
  c.kind = model::ContactKind::SingleSurface;
  c.soft = false;
  c.master_parts = {0, 1, 2};
  const std::size_t n = m.nodes.count();
  const double mass_M = 7850.0 * t * 1e-4 / 4.0;  // rho t A / 4 [kg]
  std::vector<double> mass(n, mass_M), x = m.nodes.x0, v(3 * n, 0.0), f(3 * n, 0.0);
  ContactInterface ci(m, c, mass.data());
  ci.compute(x.data(), v.data(), 0.0, f.data());
  const double K = 210e9 / (3.0 * (1.0 - 0.6));
  const double k = 0.1 * K * 0.0016 / (0.04 * std::sqrt(2.0));
  // omega dt = 0.13: the tube's soft springs (0.1 m_eff / dt0^2) on its corner nodes
  const double dt = 0.13 * std::sqrt(mass_M / k), period = 2e-5;
  const int steps = static_cast<int>(period / dt) + 1;
  const auto gap = [&](double time) {  // mid-surface distance of A and B [m]
    const double s = std::min(time / period, 1.0);
    return g_open - 0.5 * (g_open - g_closed) * (1.0 - std::cos(2.0 * M_PI * s));
  };
  double p_max = 0.0;
  ContactStep r;
  for (int step = 0; step < steps; ++step) {
    const double t1 = (step + 1) * dt;
    for (std::size_t i = 8; i < 12; ++i)  // M: central difference
      for (std::size_t a = 0; a < 3; ++a) {
        v[3 * i + a] += dt * f[3 * i + a] / mass_M;
        x[3 * i + a] += dt * v[3 * i + a];
      }
    for (std::size_t i = 0; i < 8; ++i) {  // the walls: driven
      const double z1 = (i < 4 ? -0.5 : 0.5) * gap(t1);
      v[3 * i + 2] = (z1 - x[3 * i + 2]) / dt;
      x[3 * i + 2] = z1;
    }
    std::fill(f.begin(), f.end(), 0.0);
    r = ci.compute(x.data(), v.data(), dt, f.data());
    p_max = std::max(p_max, r.potential_J);
  }
  ASSERT_GT(p_max, 0.0);
  EXPECT_EQ(r.active_pairs, 0);  // open again
  EXPECT_LT(std::fabs(r.energy_J), 0.02 * p_max) << "max potential " << p_max << " J";
}

// A node inside a thin solid, nearer its top face (review of the squeezed-node spring): the
// nearest face alone pushes it out through that face. Both faces accept it (each takes up to half
// the element's initial depth, 5 mm, and the element has thinned from 10 to 6 mm); a second
// spring from the bottom face would push harder (3.5 mm against 2.5 mm) and hold it inside.
TEST(ContactInterface, NodeInAThinnedSolidLeavesThroughTheNearerFace) {
  model::Model m;
  add_steel(m);
  model::generate_box(m, steel_part("slab", 0.0), {{0, 0, 0}, {1, 1, 0.01}, {1, 1, 1}});
  const std::size_t slab_nodes = m.nodes.count();
  model::generate_box(m, steel_part("probe", 0.0), {{0.4, 0.4, 0.5}, {0.1, 0.1, 0.1}, {1, 1, 1}});
  model::Contact c;
  c.name = "probe-slab";
  c.kind = model::ContactKind::NodeToSurface;
  c.soft = false;
  const auto probe = static_cast<std::int32_t>(slab_nodes);  // the probe's first corner
  c.slave_nodes = {probe};
  c.master_parts = {0};
  m.contacts.push_back(c);
  std::vector<double> mass(m.nodes.count(), 1.0), x = m.nodes.x0, v(x.size(), 0.0);
  for (std::size_t i = 0; i < slab_nodes; ++i)
    if (x[3 * i + 2] > 0.005) x[3 * i + 2] = 0.006;  // thinned to 6 mm
  const auto p = static_cast<std::size_t>(probe);
  x[3 * p] = 0.5;
  x[3 * p + 1] = 0.5;
  x[3 * p + 2] = 0.0035;  // 2.5 mm under the top face, 3.5 mm above the bottom one
  std::vector<double> f(x.size(), 0.0);
  ContactInterface ci(m, m.contacts[0], mass.data());
  ci.compute(x.data(), v.data(), 0.0, f.data());
  EXPECT_GT(f[3 * p + 2], 0.0) << "pushed towards the mid-plane: held inside the solid";
}
