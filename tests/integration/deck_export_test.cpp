// The deck writer's round trip (issue #22 acceptance 1): `crashlink export` of the two main
// scenes, read back with the deck reader, gives the same model to the bit (node positions,
// elements in the same order, sections, materials, constraints, rigid bodies, contacts, probes,
// controls, domains), and running it gives the same answer to the bit, mono and multi.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "solver/contact/segments.h"
#include "solver/cosim/layer_network.h"
#include "solver/deck/model_from_deck.h"
#include "solver/deck_writer/deck_writer.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

const std::string kScenes = std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/";
const std::string kCrashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";

std::filesystem::path temp_dir(const std::string& tag) {
  auto d = std::filesystem::temp_directory_path() /
           ("crashlink_export_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

/// Writes the export of `m` into `dir` (deck.k and, if any, deck.yaml); returns the model read
/// back (through the scenario when one was written).
model::Model round_trip(const model::Model& m, const std::filesystem::path& dir,
                        deck_writer::ExportText* text_out = nullptr) {
  const auto text =
      deck_writer::export_deck(m, *deck::find_unit_system("m-kg-s"), "deck.k", "test");
  std::ofstream(dir / "deck.k") << text.deck;
  if (text_out) *text_out = text;
  if (text.scenario.empty())
    return deck::read_deck((dir / "deck.k").string(), {"m-kg-s", {}}).model;
  std::ofstream(dir / "deck.yaml") << text.scenario;
  return io::read_scenario((dir / "deck.yaml").string());
}

/// Exactly, or within 1e-9 of the curve's largest value where a sample falls on a step (a VAD 2
/// curve's steps are 1e-6 of a segment wide: the round-off of their abscissae moves the value).
void expect_same_curve(const model::Curve& a, const model::Curve& b, double end) {
  double top = 0.0;
  for (double v : a.value) top = std::max(top, std::abs(v));
  for (int k = 0; k <= 100; ++k)
    EXPECT_NEAR(a.at(end * k / 100.0), b.at(end * k / 100.0), 1e-9 * top);
}

/// Every field the run reads, compared exactly (names where the deck keeps them).
void expect_same_model(const model::Model& a, const model::Model& d,
                       std::size_t rounded_coordinates) {
  EXPECT_EQ(d.name, a.name);
  ASSERT_EQ(d.nodes.count(), a.nodes.count());
  EXPECT_EQ(d.nodes.id, a.nodes.id);
  // To the bit where LS-DYNA's 20 columns hold the 17 digits a double may need; else within
  // the round-off of the model's size (a coordinate of 1e-18 m generator noise, or 17 digits
  // below 1 cm, written to 16 digits).
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.nodes.x0.size(); ++i)
    if (d.nodes.x0[i] != a.nodes.x0[i]) {
      ++differ;
      EXPECT_NEAR(d.nodes.x0[i], a.nodes.x0[i], 1e-16 * (1.0 + std::abs(a.nodes.x0[i])));
    }
  EXPECT_LE(differ, rounded_coordinates) << "coordinates not bit-equal";
  ASSERT_EQ(d.materials.size(), a.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const auto &x = a.materials[i], &y = d.materials[i];
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.kind, x.kind);
    EXPECT_EQ(y.density_kg_m3, x.density_kg_m3);
    EXPECT_EQ(y.youngs_modulus_Pa, x.youngs_modulus_Pa);
    EXPECT_EQ(y.poisson_ratio, x.poisson_ratio);
    if (x.hardening.eps_p.size() == 1) {  // a constant curve is written with a second point
      for (double ep : {0.0, 0.01, 0.1, 1.0, 3.0})
        EXPECT_EQ(y.hardening.yield(ep), x.hardening.yield(ep));
    } else {
      EXPECT_EQ(y.hardening.eps_p, x.hardening.eps_p);
      EXPECT_EQ(y.hardening.sigma_y_Pa, x.hardening.sigma_y_Pa);
    }
    EXPECT_EQ(y.rate_c_per_s, x.rate_c_per_s);
    EXPECT_EQ(y.rate_p, x.rate_p);
  }
  ASSERT_EQ(d.parts.size(), a.parts.size());
  for (std::size_t p = 0; p < a.parts.size(); ++p) {
    SCOPED_TRACE(a.parts[p].name);
    const auto &x = a.parts[p], &y = d.parts[p];
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.kind, x.kind);
    EXPECT_EQ(y.material, x.material);
    EXPECT_EQ(y.connectivity, x.connectivity);
    EXPECT_EQ(y.element_id, x.element_id);
    EXPECT_EQ(y.thickness_m, x.thickness_m);
    EXPECT_EQ(y.element_thickness_m, x.element_thickness_m);
    EXPECT_EQ(y.element_density_scale, x.element_density_scale);
    if (x.kind == model::ElementKind::Shell4) {
      EXPECT_EQ(y.through_thickness_points, x.through_thickness_points);
    }
    EXPECT_EQ(y.hourglass_coefficient, x.hourglass_coefficient);
  }
  EXPECT_EQ(d.fixed, a.fixed);
  // initial velocities: a rigid body's nodes take the body's (the deck leaves them out)
  const auto free_nodes = [](const model::Model& m, std::vector<std::int32_t> nodes) {
    std::vector<char> body(m.nodes.count(), 0);
    for (const auto& rb : m.rigid_bodies) {
      for (int p : rb.parts)
        for (auto c : m.parts[static_cast<std::size_t>(p)].connectivity)
          body[static_cast<std::size_t>(c)] = 1;
      for (auto c : rb.nodes) body[static_cast<std::size_t>(c)] = 1;
    }
    std::erase_if(nodes, [&](std::int32_t c) { return body[static_cast<std::size_t>(c)] != 0; });
    return nodes;
  };
  ASSERT_EQ(d.initial_velocities.size(), a.initial_velocities.size());
  for (std::size_t k = 0; k < a.initial_velocities.size(); ++k) {
    EXPECT_EQ(free_nodes(d, d.initial_velocities[k].nodes),
              free_nodes(a, a.initial_velocities[k].nodes));
    EXPECT_EQ(d.initial_velocities[k].velocity_m_s, a.initial_velocities[k].velocity_m_s);
  }
  ASSERT_EQ(d.prescribed_velocities.size(), a.prescribed_velocities.size());
  for (std::size_t k = 0; k < a.prescribed_velocities.size(); ++k) {
    EXPECT_EQ(d.prescribed_velocities[k].nodes, a.prescribed_velocities[k].nodes);
    EXPECT_EQ(d.prescribed_velocities[k].dof, a.prescribed_velocities[k].dof);
    EXPECT_EQ(d.prescribed_velocities[k].rigid_body, a.prescribed_velocities[k].rigid_body);
    expect_same_curve(d.prescribed_velocities[k].velocity, a.prescribed_velocities[k].velocity,
                      a.controls.end_time_s);
  }
  ASSERT_EQ(d.loads.size(), a.loads.size());
  for (std::size_t k = 0; k < a.loads.size(); ++k) {
    EXPECT_EQ(d.loads[k].nodes, a.loads[k].nodes);
    EXPECT_EQ(d.loads[k].dof, a.loads[k].dof);
    expect_same_curve(d.loads[k].force, a.loads[k].force, a.controls.end_time_s);
  }
  ASSERT_EQ(d.rigid_bodies.size(), a.rigid_bodies.size());
  for (std::size_t b = 0; b < a.rigid_bodies.size(); ++b) {
    const auto &x = a.rigid_bodies[b], &y = d.rigid_bodies[b];
    EXPECT_EQ(y.parts, x.parts);
    EXPECT_EQ(y.velocity_m_s, x.velocity_m_s);
    EXPECT_EQ(y.angular_velocity_rad_s, x.angular_velocity_rad_s);
    if (x.mass_kg > 0.0) {
      EXPECT_EQ(y.mass_kg, x.mass_kg);
    }
    if (x.inertia_given) {  // to the bit, or within the round-off of 16 written digits
      for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c)
          EXPECT_NEAR(y.inertia_kg_m2[r][c], x.inertia_kg_m2[r][c],
                      rounded_coordinates > 0 ? 1e-15 * std::abs(x.inertia_kg_m2[r][c]) : 0.0);
    }
    EXPECT_EQ(y.nodes, x.nodes);
    EXPECT_EQ(y.fixed, x.fixed);
  }
  ASSERT_EQ(d.contacts.size(), a.contacts.size());
  for (std::size_t k = 0; k < a.contacts.size(); ++k) {
    const auto &x = a.contacts[k], &y = d.contacts[k];
    SCOPED_TRACE(x.name);
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.kind, x.kind);
    EXPECT_EQ(y.slave_nodes, x.slave_nodes);
    EXPECT_EQ(y.master_parts, x.master_parts);
    // Faces given by a segment set are the ones the model derives from its slave nodes.
    const auto faces = [&](const model::Model& m, const model::Contact& c) {
      return c.slave_faces.empty() && c.kind == model::ContactKind::SurfaceToSurface
                 ? contact::slave_faces(m, c.slave_nodes, c.master_parts)
                 : c.slave_faces;
    };
    EXPECT_EQ(faces(d, y), faces(a, x));
    EXPECT_EQ(y.penalty_scale, x.penalty_scale);
    EXPECT_EQ(y.soft, x.soft);
    EXPECT_EQ(y.soft_scale, x.soft_scale);
    EXPECT_EQ(y.static_friction, x.static_friction);
    if (x.friction_decay_s_m > 0.0) {
      EXPECT_EQ(y.dynamic_friction, x.dynamic_friction);
    }
    EXPECT_EQ(y.friction_decay_s_m, x.friction_decay_s_m);
    EXPECT_EQ(y.slave_thickness_m, x.slave_thickness_m);
    EXPECT_EQ(y.master_thickness_m, x.master_thickness_m);
  }
  std::map<std::string, std::pair<model::Probe::Kind, int>> pa, pd;
  for (const auto& p : a.probes) pa[p.name] = {p.kind, p.index};
  for (const auto& p : d.probes) pd[p.name] = {p.kind, p.index};
  EXPECT_EQ(pd, pa);
  const auto &c = a.controls, &e = d.controls;
  EXPECT_EQ(e.end_time_s, c.end_time_s);
  EXPECT_EQ(e.dt_scale, c.dt_scale);
  EXPECT_EQ(e.dt_max_s, c.dt_max_s);
  EXPECT_EQ(e.history_interval_s, c.history_interval_s);
  EXPECT_EQ(e.field_interval_s, c.field_interval_s);
  EXPECT_EQ(e.bulk_q_linear, c.bulk_viscosity ? c.bulk_q_linear : 0.0);
  EXPECT_EQ(e.bulk_q_quadratic, c.bulk_viscosity ? c.bulk_q_quadratic : 0.0);
  EXPECT_EQ(e.shell_bulk_viscosity, c.shell_bulk_viscosity);
  EXPECT_EQ(e.energy_tolerance, c.energy_tolerance);
  EXPECT_EQ(e.gravity_m_s2, c.gravity_m_s2);
  EXPECT_EQ(e.mass_scaling_dt_s, c.mass_scaling_dt_s);
  ASSERT_EQ(d.domains.size(), a.domains.size());
  for (std::size_t k = 0; k < a.domains.size(); ++k) {
    EXPECT_EQ(d.domains[k].name, a.domains[k].name);
    EXPECT_EQ(d.domains[k].parts, a.domains[k].parts);
  }
  EXPECT_EQ(d.coupling.interface_damping.ratio, a.coupling.interface_damping.ratio);
}

/// The rigid walls: names, nodes, shapes and sizes (the normal and edge rebuilt from points one
/// length unit apart: within round-off).
void expect_same_walls(const model::Model& m, const model::Model& back) {
  ASSERT_EQ(back.rigid_walls.size(), m.rigid_walls.size());
  for (std::size_t k = 0; k < m.rigid_walls.size(); ++k) {
    const auto &a = m.rigid_walls[k], &b = back.rigid_walls[k];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.nodes, a.nodes);
    EXPECT_EQ(b.mass_kg, a.mass_kg);
    EXPECT_EQ(b.velocity_m_s, a.velocity_m_s);
    EXPECT_EQ(b.shape, a.shape);
    EXPECT_EQ(b.length_m, a.length_m);
    EXPECT_EQ(b.width_m, a.width_m);
    EXPECT_EQ(b.radius_m, a.radius_m);
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_NEAR(b.point_m[j], a.point_m[j], 1e-15);
      EXPECT_NEAR(b.normal[j], a.normal[j], 1e-15);
      EXPECT_NEAR(b.edge[j], a.edge[j], 1e-15);
    }
  }
}

TEST(DeckExport, PlateImpactReadsBackToTheSameModel) {
  const model::Model yaml = io::read_scenario(kScenes + "plate_impact.yaml");
  deck_writer::ExportText text;
  const model::Model deck = round_trip(yaml, temp_dir("plate"), &text);
  expect_same_model(yaml, deck, 0);
  EXPECT_TRUE(text.scenario.empty()) << "no domains: the deck says everything";
}

TEST(DeckExport, HeadImpactReadsBackToTheSameModel) {
  const model::Model yaml = io::read_scenario(kScenes + "head_impact.yaml");
  deck_writer::ExportText text;
  const model::Model deck = round_trip(yaml, temp_dir("head"), &text);
  expect_same_model(yaml, deck, text.rounding.rounded);
  std::printf("[measured] head impact export: %zu values rounded, largest %.2e relative\n",
              text.rounding.rounded, text.rounding.max_relative);
  EXPECT_LT(text.rounding.max_relative, 1e-13);
  EXPECT_FALSE(text.scenario.empty()) << "the domains go into a scenario naming the deck";
  for (const auto& n : text.notes) std::printf("[export note] %s\n", n.c_str());
}

/// Decks other people (and earlier sessions) wrote, read in mm-t-s, exported in SI and read
/// back: the moving wall, single-surface contact, rate-dependent MAT_024 (tube), nodal loads and
/// prescribed motions (cantilever, twin), per-element thickness, symmetry planes (Taylor bar).
TEST(DeckExport, DecksReadBackToTheSameModel) {
  const std::string data = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/";
  for (const std::string deck :
       {"tube/tube_crush.k", "cantilever.k", "twin/main.k", "ansys/Taylor_Bar/taylor_bar_275.k",
        "ansys/Bar_Impact/bar_on_plate.k", "two_rates/two_rates.k"}) {
    SCOPED_TRACE(deck);
    const model::Model m = deck::read_deck(data + deck, {"mm-t-s", {}}).model;
    deck_writer::ExportText text;
    const auto dir = temp_dir("decks");
    const model::Model back = round_trip(m, dir, &text);
    expect_same_model(m, back, text.rounding.rounded);
    expect_same_walls(m, back);
    std::printf("[measured] %s: %zu values rounded (largest %.1e relative)\n", deck.c_str(),
                text.rounding.rounded, text.rounding.max_relative);
    EXPECT_LT(text.rounding.max_relative, 1e-13);
    std::filesystem::remove_all(dir);
  }
}

/// Another unit system (cm-g-us: every factor other than 1): the tube crush deck (moving wall,
/// Cowper-Symonds C, single-surface contact with friction decay), the twin (loads, prescribed
/// motion, gravity, rigid body) and the two-rate bar with DT2MS read back to their model within
/// the round-off of the conversions.
TEST(DeckExport, OtherUnitsReadBackWithinRoundOff) {
  const std::string data = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/";
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::abs(b); };
  for (const std::string deck : {"tube/tube_crush.k", "twin/main.k", "cantilever.k"}) {
    SCOPED_TRACE(deck);
    const model::Model m = deck::read_deck(data + deck, {"mm-t-s", {}}).model;
    const auto dir = temp_dir("units");
    const auto text = deck_writer::export_deck(m, *deck::find_unit_system("cm-g-us"), "d.k", "t");
    std::ofstream(dir / "d.k") << text.deck;
    const model::Model b = deck::read_deck((dir / "d.k").string(), {"cm-g-us", {}}).model;
    ASSERT_EQ(b.nodes.count(), m.nodes.count());
    for (std::size_t i = 0; i < m.nodes.x0.size(); ++i)
      ASSERT_NEAR(b.nodes.x0[i], m.nodes.x0[i], 1e-15);
    for (std::size_t k = 0; k < m.materials.size(); ++k) {
      EXPECT_TRUE(near(b.materials[k].density_kg_m3, m.materials[k].density_kg_m3));
      EXPECT_TRUE(near(b.materials[k].youngs_modulus_Pa, m.materials[k].youngs_modulus_Pa));
      EXPECT_TRUE(near(b.materials[k].rate_c_per_s, m.materials[k].rate_c_per_s));
      for (std::size_t j = 0; j < m.materials[k].hardening.sigma_y_Pa.size(); ++j)
        EXPECT_TRUE(
            near(b.materials[k].hardening.sigma_y_Pa[j], m.materials[k].hardening.sigma_y_Pa[j]));
    }
    for (std::size_t p = 0; p < m.parts.size(); ++p)
      EXPECT_TRUE(near(b.parts[p].thickness_m, m.parts[p].thickness_m) ||
                  m.parts[p].thickness_m == 0.0);
    ASSERT_EQ(b.contacts.size(), m.contacts.size());
    for (std::size_t k = 0; k < m.contacts.size(); ++k) {
      EXPECT_TRUE(near(b.contacts[k].friction_decay_s_m, m.contacts[k].friction_decay_s_m) ||
                  m.contacts[k].friction_decay_s_m == 0.0);
      EXPECT_EQ(b.contacts[k].static_friction, m.contacts[k].static_friction);
    }
    ASSERT_EQ(b.rigid_walls.size(), m.rigid_walls.size());
    for (std::size_t k = 0; k < m.rigid_walls.size(); ++k) {
      EXPECT_TRUE(near(b.rigid_walls[k].mass_kg, m.rigid_walls[k].mass_kg));
      EXPECT_TRUE(near(b.rigid_walls[k].velocity_m_s, m.rigid_walls[k].velocity_m_s));
    }
    ASSERT_EQ(b.rigid_bodies.size(), m.rigid_bodies.size());
    for (std::size_t k = 0; k < m.rigid_bodies.size(); ++k)
      for (std::size_t d = 0; d < 3; ++d)
        EXPECT_NEAR(b.rigid_bodies[k].velocity_m_s[d], m.rigid_bodies[k].velocity_m_s[d], 1e-12);
    for (std::size_t k = 0; k < m.loads.size(); ++k)
      for (double t : {0.0, 0.3 * m.controls.end_time_s, m.controls.end_time_s})
        EXPECT_NEAR(b.loads[k].force.at(t), m.loads[k].force.at(t),
                    1e-12 * (1.0 + std::abs(m.loads[k].force.at(t))));
    for (std::size_t k = 0; k < m.prescribed_velocities.size(); ++k)
      for (double t : {0.0, 0.3 * m.controls.end_time_s, m.controls.end_time_s})
        EXPECT_NEAR(b.prescribed_velocities[k].velocity.at(t),
                    m.prescribed_velocities[k].velocity.at(t),
                    1e-12 * (1.0 + std::abs(m.prescribed_velocities[k].velocity.at(t))));
    for (std::size_t d = 0; d < 3; ++d)
      EXPECT_NEAR(b.controls.gravity_m_s2[d], m.controls.gravity_m_s2[d], 1e-12);
    EXPECT_TRUE(near(b.controls.end_time_s, m.controls.end_time_s));
    EXPECT_TRUE(near(b.controls.history_interval_s, m.controls.history_interval_s) ||
                m.controls.history_interval_s == 0.0);
    std::filesystem::remove_all(dir);
  }
}

/// Mass scaling goes out as DT2MS and comes back as the same density factors, to the bit.
TEST(DeckExport, MassScaledDeckReadsBackWithItsFactors) {
  const auto dir = temp_dir("dt2ms");
  const std::string src = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/two_rates/";
  std::ifstream in(src + "two_rates.k");
  std::stringstream t;
  t << in.rdbuf();
  std::string k = t.str();
  k.replace(k.find("*CONTROL_TIMESTEP\n                 0.9\n"), 37,
            "*CONTROL_TIMESTEP\n,0.9,,,-1.0e-6\n");
  std::filesystem::copy_file(src + "bar_nodes.k", dir / "bar_nodes.k",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "in.k") << k;
  const model::Model m = deck::read_deck((dir / "in.k").string(), {"mm-t-s", {}}).model;
  ASSERT_FALSE(m.parts[1].element_density_scale.empty());
  deck_writer::ExportText text;
  const model::Model back = round_trip(m, dir, &text);
  expect_same_model(m, back, text.rounding.rounded);
  EXPECT_NE(text.deck.find("-1e-6"), std::string::npos) << "DT2MS written";
  std::filesystem::remove_all(dir);
}

/// Rigid bodies beyond one part: two rigid parts with extra nodes of a deformable plate
/// (*CONSTRAINED_RIGID_BODIES, *CONSTRAINED_EXTRA_NODES_SET) and a nodal rigid body over a strip
/// of another plate, moving (*CONSTRAINED_NODAL_RIGID_BODY and *INITIAL_VELOCITY on its nodes):
/// the same model read back, and the same run (to round-off) over 0.3 ms.
TEST(DeckExport, RigidBodiesOfSeveralPartsAndOfNodesReadBack) {
  const model::Model yaml = io::parse_scenario(R"(name: bodies
controls: {end_time: 3.0e-4, history_interval: 1.0e-5}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
  block: {type: rigid, density: 7850.0}
parts:
  flap: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.1, 0.05], normal: z, divisions: [10, 5]}}
  hinge_a: {material: block, element: shell4, thickness: 2.0e-3, mesh: {generator: plate, origin: [-0.02, 0, 0.01], size: [0.02, 0.05], normal: z, divisions: [2, 5]}}
  hinge_b: {material: block, element: shell4, thickness: 2.0e-3, mesh: {generator: plate, origin: [-0.02, 0, -0.01], size: [0.02, 0.05], normal: z, divisions: [2, 5]}}
  sheet: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0.1, 0], size: [0.1, 0.05], normal: z, divisions: [10, 5]}}
initial_velocity:   # the sheet moves; its clamp (a nodal body in it) at its own velocity
  - {part: sheet, velocity: [0.0, 0.0, -2.0]}
rigid_bodies:
  hinge: {parts: [hinge_a, hinge_b], nodes: {part: flap, box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}, angular_velocity: [0.0, 30.0, 0.0]}
  clamp: {nodes: {part: sheet, box: {min: [0.0999, -1, -1], max: [1, 1, 1]}}, velocity: [0.0, 0.0, 1.5]}
probes:
  hinge_a: {rigid_body: hinge}   # the deck names a body after its lead part
  clamp: {rigid_body: clamp}
  tip: {node_near: [0.1, 0.025, 0.0], part: flap}
)",
                                               "bodies.yaml");
  ASSERT_EQ(yaml.rigid_bodies.size(), 2u);
  EXPECT_EQ(yaml.rigid_bodies[0].nodes.size(), 6u);
  EXPECT_EQ(yaml.rigid_bodies[1].nodes.size(), 6u);
  deck_writer::ExportText text;
  const model::Model deck = round_trip(yaml, temp_dir("bodies"), &text);
  expect_same_model(yaml, deck, text.rounding.rounded);
  for (const auto& n : text.notes) std::printf("[export note] %s\n", n.c_str());
  integration::Solver a(yaml), b(deck);
  a.initialize();
  b.initialize();
  double scale = 0.0, diff = 0.0;
  for (;;) {
    a.begin_cycle();
    b.begin_cycle();
    ASSERT_EQ(a.time_s(), b.time_s());
    if (a.finished()) break;
    a.end_cycle();
    b.end_cycle();
  }
  for (std::size_t i = 0; i < a.displacement().size(); ++i) {
    scale = std::max(scale, std::abs(a.displacement()[i]));
    diff = std::max(diff, std::abs(a.displacement()[i] - b.displacement()[i]));
  }
  std::printf(
      "[measured] bodies of parts and nodes, YAML and deck: max |du| %.2e of %.2e m, "
      "internal energy %.6e / %.6e J\n",
      diff, scale, a.energy().internal_J, b.energy().internal_J);
  EXPECT_GT(a.energy().internal_J, 0.0) << "the flap and the sheet flex";
  EXPECT_LE(diff, 1e-12 * scale);
}

/// Walls of every shape and a rigid body's held and prescribed dofs, from YAML to a deck and back:
/// the same model, and the same run to the bit.
TEST(DeckExport, WallsAndBodyMotionsReadBack) {
  const model::Model yaml = io::parse_scenario(R"(name: walls
controls: {end_time: 2.0e-3, history_interval: 1.0e-5}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
  ram: {type: rigid, density: 7850.0}
  anvil: {type: rigid, density: 7850.0}
parts:
  sheet: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0.001], size: [0.1, 0.05], normal: z, divisions: [10, 5]}}
  ram: {material: ram, mesh: {generator: box, origin: [0.04, 0.0, 0.003], size: [0.02, 0.05, 0.01], divisions: [2, 2, 1]}}
  anvil: {material: anvil, mesh: {generator: box, origin: [0.0, 0.1, 0.0], size: [0.01, 0.01, 0.01], divisions: [1, 1, 1]}}
node_sets:
  sheet_all: {part: sheet, box: {min: [-1, -1, -1], max: [1, 1, 1]}}
initial_velocity:
  - {part: sheet, velocity: [0.0, 0.0, -1.0]}
rigid_bodies:
  ram: {parts: [ram], fix: [x, y, rx, ry, rz]}
  anvil: {parts: [anvil], fix: all}
prescribed_velocity:
  - {name: press, rigid_body: ram, dof: z, curve: {t: [0.0, 1.0e-3, 2.0e-3], v: [0.0, -1.0, 0.0]}}
contacts:
  press_sheet: {slave: sheet_all, master: ram}
rigid_walls:
  pad: {nodes: sheet_all, point: [0.0, 0.0, 0.0], normal: [0, 0, 1], edge: [1, 0, 0], length: 0.05, width: 0.05}
  roller: {nodes: sheet_all, shape: cylinder, point: [0.05, 0.0, -0.02], axis: [0, 1, 0], radius: 0.0205, length: 0.05}
  floor: {nodes: sheet_all, point: [0.0, 0.0, -0.01], normal: [0, 0, 1], mass: 2.0, velocity: 0.5}
)",
                                               "walls.yaml");
  ASSERT_EQ(yaml.rigid_walls.size(), 3u);
  EXPECT_EQ(yaml.rigid_bodies[0].fixed,
            model::kUx | model::kUy | model::kRx | model::kRy | model::kRz);
  ASSERT_EQ(yaml.prescribed_velocities.size(), 1u);
  EXPECT_EQ(yaml.prescribed_velocities[0].rigid_body, 0);
  deck_writer::ExportText text;
  const auto dir = temp_dir("walls");
  const model::Model deck = round_trip(yaml, dir, &text);
  expect_same_model(yaml, deck, text.rounding.rounded);
  expect_same_walls(yaml, deck);
  std::filesystem::remove_all(dir);
  integration::Solver a(yaml), b(deck);
  a.initialize();
  b.initialize();
  testing::run_side_by_side(a, b, [&] { EXPECT_EQ(a.time_s(), b.time_s()); });
  EXPECT_EQ(a.displacement(), b.displacement());
  const auto& ram = a.rigid_bodies()[0];
  std::printf(
      "[measured] walls and a pressing ram, YAML and deck: ram travel %.6f mm (-1 mm "
      "prescribed), internal energy %.6e / %.6e J, floor work %.3e J\n",
      (ram.centre[2] - ram.centre0[2]) * 1e3, a.energy().internal_J, b.energy().internal_J,
      a.wall_work_J(2));
  EXPECT_NEAR(ram.centre[2] - ram.centre0[2], -1.0e-3, 1e-8);
  EXPECT_EQ(ram.centre[0], ram.centre0[0]);
  EXPECT_EQ(a.rigid_bodies()[1].centre, a.rigid_bodies()[1].centre0) << "the anvil held";
  EXPECT_GT(a.energy().internal_J, 0.0) << "the sheet bends over the pad and the roller";
}

/// Spins (*INITIAL_VELOCITY_GENERATION OMEGA) on a deformable block and a rigid one, read, written
/// and read back: every node and the body start with the same velocities (the body's written at
/// its centre in *PART_INERTIA), and run the same to the bit.
TEST(DeckExport, SpinsReadBack) {
  const auto dir = temp_dir("spins");
  std::string deck = "*KEYWORD\n*NODE\n";
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
          deck += fmt::format("{:8d}{:16.4f}{:16.4f}{:16.4f}\n", 1 + c * 8 + k * 4 + j * 2 + i,
                              static_cast<double>(i), static_cast<double>(j), 1.5 * c + k);
  deck += R"(*ELEMENT_SOLID
       1       1       1       2       4       3       5       6       8       7
       2       2       9      10      12      11      13      14      16      15
*PART
lower
         1         1         1
*PART
upper
         2         1         2
*SECTION_SOLID
         1         1
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*MAT_RIGID
         2   7.85e-9  210000.0       0.3
*INITIAL_VELOCITY_GENERATION
         1         2     100.0    1000.0       0.0       0.0
       0.5       0.5       0.0       0.0       1.0       2.0
*INITIAL_VELOCITY_GENERATION
         2         2      50.0       0.0     500.0       0.0
       0.0       0.0       0.0       1.0       0.0       0.0
*CONTROL_TERMINATION
    1.0e-5
*END
)";
  std::ofstream(dir / "spin.k") << deck;
  const model::Model m = deck::read_deck((dir / "spin.k").string(), {"mm-t-s", {}}).model;
  ASSERT_TRUE(m.rigid_bodies[0].velocity_at_point);
  deck_writer::ExportText text;
  const model::Model back = round_trip(m, dir, &text);
  integration::Solver a(m), b(back);
  a.initialize();
  b.initialize();
  for (std::size_t i = 0; i < a.velocity_mid().size(); ++i)
    EXPECT_NEAR(b.velocity_mid()[i], a.velocity_mid()[i], 1e-14) << i;
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_NEAR(b.rigid_bodies()[0].velocity[d], a.rigid_bodies()[0].velocity[d], 1e-14);
    EXPECT_EQ(b.rigid_bodies()[0].omega[d], a.rigid_bodies()[0].omega[d]);
  }
  EXPECT_NE(a.rigid_bodies()[0].velocity[2], 0.0) << "the spin about x moves the centre in z";
  testing::run_side_by_side(a, b);
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.displacement().size(); ++i) {
    scale = std::max(scale, std::abs(a.displacement()[i]));
    diff = std::max(diff, std::abs(a.displacement()[i] - b.displacement()[i]));
  }
  EXPECT_LE(diff, 1e-12 * scale);
  std::filesystem::remove_all(dir);
}

/// A deck's *DATABASE_RBDOUT probes each rigid body; a scenario naming the deck that probes a
/// body itself replaces that probe (whatever its name), and keeps the deck's node probes.
TEST(DeckExport, ScenarioProbeOfABodyReplacesTheDecksOne) {
  const auto dir = temp_dir("probes");
  (void)round_trip(io::read_scenario(kScenes + "plate_impact.yaml"), dir);
  std::ofstream(dir / "s.yaml") << "model: {deck: deck.k, units: m-kg-s}\n"
                                   "probes:\n  head: {rigid_body: headform}\n";
  const model::Model m = io::read_scenario((dir / "s.yaml").string());
  std::map<std::string, model::Probe::Kind> got;
  for (const auto& p : m.probes) got[p.name] = p.kind;
  EXPECT_EQ(
      got, (std::map<std::string, model::Probe::Kind>{{"head", model::Probe::Kind::RigidBody},
                                                      {"plate_centre", model::Probe::Kind::Node}}));
  std::filesystem::remove_all(dir);
}

/// Names a deck would read otherwise are refused, not written.
TEST(DeckExport, NamesADeckWouldMisreadAreRefused) {
  model::Model m = io::read_scenario(kScenes + "plate_impact.yaml");
  for (const auto& [bad, what] : std::vector<std::pair<std::string, std::string>>{
           {"$steel", "starts with '$' or '*'"}, {"*steel", "starts with '$' or '*'"}}) {
    model::Model x = m;
    x.materials[0].name = bad;
    try {
      (void)deck_writer::export_deck(x, *deck::find_unit_system("m-kg-s"), "d.k", "t");
      ADD_FAILURE() << bad << " was written";
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  model::Model c = m;
  c.contacts[0].name = "plate, headform";
  try {
    (void)deck_writer::export_deck(c, *deck::find_unit_system("m-kg-s"), "d.k", "t");
    ADD_FAILURE() << "a comma in a heading was written";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("holds a ','"), std::string::npos) << e.what();
  }
}

/// A model cut short at `end_s` (the runs below compare the first millisecond of contact).
model::Model shortened(model::Model m, double end_s) {
  m.controls.end_time_s = end_s;
  return m;
}

/// Mono: the YAML scene and its exported deck run the same cycles (the same steps, to the bit)
/// to the same headform accelerations and displacements to round-off. (Not to the bit: the
/// headform's centre, 1e-18 m of generator noise in x and y, needs 17 digits that LS-DYNA's 20
/// columns cannot hold, and the 1e-32 m it moves reaches the last bits of the contact forces.)
TEST(DeckExport, PlateImpactDeckRunsAsTheScenario) {
  const model::Model yaml = shortened(io::read_scenario(kScenes + "plate_impact.yaml"), 1.5e-3);
  const model::Model deck = round_trip(yaml, temp_dir("plate_run"));
  integration::Solver a(yaml), b(deck);
  a.initialize();
  b.initialize();
  std::size_t cycles = 0;
  double peak = 0.0, diff = 0.0;
  for (;;) {
    a.begin_cycle();
    b.begin_cycle();
    ASSERT_EQ(a.time_s(), b.time_s()) << "after " << cycles << " cycles";
    const auto va = a.probe(yaml.probes[0]).acceleration_m_s2;  // the headform
    const auto vb = b.probe(deck.probes[0]).acceleration_m_s2;
    peak = std::max(peak, norm(va));
    diff = std::max(diff, norm(va - vb));
    if (a.finished() || b.finished()) break;
    a.end_cycle();
    b.end_cycle();
    ++cycles;
  }
  EXPECT_TRUE(a.finished() && b.finished());
  double u_scale = 0.0, u_diff = 0.0;
  for (std::size_t i = 0; i < a.displacement().size(); ++i) {
    u_scale = std::max(u_scale, std::abs(a.displacement()[i]));
    u_diff = std::max(u_diff, std::abs(a.displacement()[i] - b.displacement()[i]));
  }
  std::printf(
      "[measured] plate impact, YAML and exported deck: %zu cycles to %.2f ms, peak %.1f "
      "g, max |da| %.2e of it, max |du| %.2e of max |u| %.2e m\n",
      cycles, 1e3 * a.time_s(), peak / 9.81, diff / peak, u_diff / u_scale, u_scale);
  EXPECT_GT(peak, 100.0 * 9.81) << "the headform has struck the plate";
  EXPECT_LE(diff, 1e-10 * peak);
  EXPECT_LE(u_diff, 1e-10 * u_scale);
}

/// Multi (the layer scheme in-process, the head-impact scene's two domains at their own steps):
/// the scenario the export writes beside the deck gives the same run as the YAML.
TEST(DeckExport, HeadImpactDeckRunsInMultiAsTheScenario) {
  const model::Model yaml = shortened(io::read_scenario(kScenes + "head_impact.yaml"), 1.0e-3);
  const model::Model deck = round_trip(yaml, temp_dir("head_run"));
  ASSERT_EQ(deck.domains.size(), 2u);
  cosim::LayerNetworkOptions o;
  o.step_safety = 0.9;
  cosim::LayerNetwork a(yaml, o), b(deck, o);
  a.initialize();
  b.initialize();
  ASSERT_TRUE(a.run());
  ASSERT_TRUE(b.run());
  const auto ua = a.global_displacement(), ub = b.global_displacement();
  ASSERT_EQ(ua.size(), ub.size());
  double scale = 0.0, diff = 0.0;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < ua.size(); ++i) {
    scale = std::max(scale, std::abs(ua[i]));
    diff = std::max(diff, std::abs(ua[i] - ub[i]));
    differ += ua[i] != ub[i] ? 1 : 0;
  }
  const auto ea = a.energy(), eb = b.energy();
  std::printf(
      "[measured] head impact multi, YAML and exported deck at 1 ms: max |du| %.2e m of "
      "max |u| %.2e m, %zu of %zu values differ; internal energy %.9e / %.9e J\n",
      diff, scale, differ, ua.size(), ea.internal_J, eb.internal_J);
  EXPECT_GT(scale, 1e-4) << "the hood has been struck";
  EXPECT_LE(diff, 1e-12 * scale);
  EXPECT_NEAR(eb.internal_J, ea.internal_J, 1e-9 * ea.internal_J);
}

/// The command: the deck and the scenario beside it written, how to run them printed; what a
/// deck cannot hold refused with exit 2 and the fix, nothing written.
TEST(DeckExport, CommandWritesTheDeckAndTheScenarioOrRefuses) {
  const auto dir = temp_dir("cli");
  int status = 0;
  std::string out =
      testing::run_command(kCrashlink + " export " + kScenes + "head_impact.yaml --deck " +
                               (dir / "head.k").string() + " 2>&1",
                           status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("15431 nodes, 14172 elements, 7 parts, 3 contacts, units m-kg-s"),
            std::string::npos)
      << out;
  EXPECT_NE(
      out.find("run it with `crashlink run " + (dir / "head.yaml").string() + " --mode multi`"),
      std::string::npos)
      << out;
  EXPECT_TRUE(std::filesystem::exists(dir / "head.yaml"));
  EXPECT_FALSE(std::filesystem::exists(dir / "head.k.tmp"));

  // mm-t-s: the numbers a crash engineer reads (the round trip then to round-off)
  out = testing::run_command(kCrashlink + " export " + kScenes + "plate_impact.yaml --deck " +
                                 (dir / "plate_mm.k").string() + " --units mm-t-s 2>&1",
                             status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  const model::Model mm = deck::read_deck((dir / "plate_mm.k").string(), {"mm-t-s", {}}).model;
  const model::Model si = io::read_scenario(kScenes + "plate_impact.yaml");
  ASSERT_EQ(mm.nodes.count(), si.nodes.count());
  for (std::size_t i = 0; i < si.nodes.x0.size(); ++i)
    ASSERT_NEAR(mm.nodes.x0[i], si.nodes.x0[i], 1e-15);
  EXPECT_NEAR(mm.materials[0].youngs_modulus_Pa, si.materials[0].youngs_modulus_Pa, 1e-3);
  EXPECT_NEAR(mm.rigid_bodies[0].velocity_m_s[2], -9.72, 1e-14);

  // the scenario beside a deck named after the input would overwrite it: refused
  std::filesystem::copy_file(kScenes + "head_impact.yaml", dir / "head_impact.yaml");
  out = testing::run_command(kCrashlink + " export " + (dir / "head_impact.yaml").string() +
                                 " --deck " + (dir / "head_impact.k").string() + " 2>&1",
                             status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("would overwrite the scenario being exported"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "head_impact.k"));

  // a nodal rigid body with its own mass: *CONSTRAINED_NODAL_RIGID_BODY_INERTIA, read back
  // with it; with held dofs too (_SPC, another form of the keyword): refused
  const std::string nrb = R"(name: nrb
controls: {end_time: 1.0e-4}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  a: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.1, 0.1], normal: z, divisions: [2, 2]}}
rigid_bodies:
  body: {nodes: {part: a, box: {min: [-1, -1, -1], max: [0.01, 1, 1]}}, mass: 1.0, velocity: [0, 0, 2.0]}
)";
  std::ofstream(dir / "nrb.yaml") << nrb;
  out = testing::run_command(kCrashlink + " export " + (dir / "nrb.yaml").string() + " --deck " +
                                 (dir / "nrb.k").string() + " 2>&1",
                             status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  {
    const model::Model back = deck::read_deck((dir / "nrb.k").string(), {"m-kg-s", {}}).model;
    ASSERT_EQ(back.rigid_bodies.size(), 1u);
    EXPECT_EQ(back.rigid_bodies[0].name, "body");
    EXPECT_EQ(back.rigid_bodies[0].mass_kg, 1.0);
    EXPECT_EQ(back.rigid_bodies[0].velocity_m_s[2], 2.0);
    EXPECT_TRUE(back.rigid_bodies[0].inertia_given);
  }
  std::ofstream(dir / "nrb2.yaml") << nrb.substr(0, nrb.size() - 2) + ", fix: [x]}\n";
  out = testing::run_command(kCrashlink + " export " + (dir / "nrb2.yaml").string() + " --deck " +
                                 (dir / "nrb2.k").string() + " 2>&1",
                             status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("rigid body 'body' of nodes only has both a given mass or inertia"),
            std::string::npos)
      << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "nrb2.k"));
  out = testing::run_command(kCrashlink + " export " + kScenes + "plate_impact.yaml --deck " +
                                 (dir / "p.k").string() + " --units furlong 2>&1",
                             status);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("--units furlong is not a unit system; fix: one of mm-t-s"), std::string::npos)
      << out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace crashlink
