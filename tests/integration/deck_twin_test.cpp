// The twin deck (issue #22 acceptance 2): tests/data/decks/twin/main.k uses every keyword the
// reader supports, in fixed, long and free format across three files joined by *INCLUDE, with
// *PARAMETERs, in mm-t-s; twin.yaml builds the same model in SI from crashlink's generators. The
// deck numbers its nodes itself, so nodes are matched by position (1 nm) and everything that
// names nodes is compared through that map: elements (corners in order), sections, materials,
// held dofs, initial velocities, rigid bodies (parts, extra nodes, mass, inertia, held dofs,
// spot-weld failure), prescribed motions and loads with their curves, gravity, contacts (slave
// nodes and faces, masters, penalty, soft, friction), rigid walls of every shape, probes and
// controls. Both then run to the end with the same answer.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "solver/contact/segments.h"
#include "solver/deck/deck.h"
#include "solver/deck/model_from_deck.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

const std::string kDir = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/twin/";

/// Relative tolerance of the unit conversions (mm-t-s to SI: one or two roundings).
constexpr double kRel = 1e-14;

bool near(double a, double b, double rel = kRel) {
  return std::abs(a - b) <= rel * std::max({std::abs(a), std::abs(b), 1e-300});
}

/// A node's position rounded to 1 nm, as a key.
using Key = std::array<long long, 3>;
Key key(const model::Model& m, std::int32_t i) {
  const auto k = static_cast<std::size_t>(i);
  return {std::llround(m.nodes.x0[3 * k] * 1e9), std::llround(m.nodes.x0[3 * k + 1] * 1e9),
          std::llround(m.nodes.x0[3 * k + 2] * 1e9)};
}

/// Node lists as sorted positions (order-free comparison of two models' node sets).
std::vector<Key> keys(const model::Model& m, const std::vector<std::int32_t>& nodes) {
  std::vector<Key> out;
  for (auto i : nodes) out.push_back(key(m, i));
  std::sort(out.begin(), out.end());
  return out;
}

/// Faces (4 nodes each) as the sorted list of their corners' positions in order.
std::vector<std::vector<Key>> faces(const model::Model& m, const std::vector<std::int32_t>& f) {
  std::vector<std::vector<Key>> out;
  for (std::size_t k = 0; 4 * k < f.size(); ++k)
    out.push_back(
        {key(m, f[4 * k]), key(m, f[4 * k + 1]), key(m, f[4 * k + 2]), key(m, f[4 * k + 3])});
  std::sort(out.begin(), out.end());
  return out;
}

/// Every element of part p as the positions of its corners in order, sorted.
std::vector<std::vector<Key>> elements(const model::Model& m, std::size_t p) {
  const auto& part = m.parts[p];
  const std::size_t k = static_cast<std::size_t>(model::nodes_per_element(part.kind));
  std::vector<std::vector<Key>> out;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    std::vector<Key> corners;
    for (std::size_t j = 0; j < k; ++j) corners.push_back(key(m, part.connectivity[k * e + j]));
    out.push_back(corners);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> part_names(const model::Model& m, const std::vector<int>& parts) {
  std::vector<std::string> out;
  for (int p : parts) out.push_back(m.parts[static_cast<std::size_t>(p)].name);
  std::sort(out.begin(), out.end());
  return out;
}

/// Per node position: held dofs and the initial velocity it ends with (later entries override,
/// the nodes of rigid bodies left out: they take their body's).
std::map<Key, std::pair<int, Vec3>> node_conditions(const model::Model& m) {
  std::set<Key> body;
  for (const auto& rb : m.rigid_bodies) {
    for (int p : rb.parts)
      for (auto c : m.parts[static_cast<std::size_t>(p)].connectivity) body.insert(key(m, c));
    for (auto c : rb.nodes) body.insert(key(m, c));
  }
  std::map<Key, std::pair<int, Vec3>> out;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    out[key(m, static_cast<std::int32_t>(i))] = {m.fixed[i], Vec3{}};
  for (const auto& iv : m.initial_velocities)
    for (auto i : iv.nodes) {
      const auto k = static_cast<std::size_t>(i);
      if (!body.count(key(m, i)))  // (a spin's velocity at the node's own position)
        out[key(m, i)].second =
            iv.at({m.nodes.x0[3 * k], m.nodes.x0[3 * k + 1], m.nodes.x0[3 * k + 2]});
    }
  return out;
}

/// Curves compared between their sample points' midpoints (a VAD 2 curve's steps are 1e-6 of a
/// segment wide: the twin writes them as its own narrow steps).
void expect_same_curve(const model::Curve& a, const model::Curve& b, double end) {
  for (int k = 0; k < 100; ++k) {
    const double t = end * (k + 0.5) / 100.0;
    EXPECT_TRUE(near(a.at(t), b.at(t), 1e-12)) << "t " << t << ": " << a.at(t) << " vs " << b.at(t);
  }
}

void expect_same_material(const materials::Material& a, const materials::Material& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_TRUE(near(a.density_kg_m3, b.density_kg_m3));
  EXPECT_TRUE(near(a.youngs_modulus_Pa, b.youngs_modulus_Pa));
  EXPECT_EQ(a.poisson_ratio, b.poisson_ratio);
  ASSERT_EQ(a.hardening.eps_p.size(), b.hardening.eps_p.size());
  for (std::size_t i = 0; i < a.hardening.eps_p.size(); ++i) {
    EXPECT_TRUE(near(a.hardening.eps_p[i], b.hardening.eps_p[i]));
    EXPECT_TRUE(near(a.hardening.sigma_y_Pa[i], b.hardening.sigma_y_Pa[i]));
  }
  EXPECT_EQ(a.rate_c_per_s, b.rate_c_per_s);
  EXPECT_EQ(a.rate_p, b.rate_p);
}

template <class T, class F>
const T& by_name(const std::vector<T>& v, const std::string& name, F&& name_of) {
  for (const auto& x : v)
    if (name_of(x) == name) return x;
  ADD_FAILURE() << "no '" << name << "'";
  return v.front();
}

void expect_same_vec(const Vec3& a, const Vec3& b) {
  for (std::size_t c = 0; c < 3; ++c) EXPECT_TRUE(near(a[c], b[c])) << a[c] << " vs " << b[c];
}

TEST(DeckTwin, DeckGivesTheModelOfItsYamlTwin) {
  const model::Model yaml = io::read_scenario(kDir + "twin.yaml");
  const deck::DeckRead read = deck::read_deck(kDir + "main.k", {"mm-t-s", {}});
  const model::Model& deck = read.model;
  EXPECT_EQ(deck.name, yaml.name);
  ASSERT_EQ(deck.nodes.count(), yaml.nodes.count());
  // parts, by name
  ASSERT_EQ(deck.parts.size(), yaml.parts.size());
  for (std::size_t q = 0; q < yaml.parts.size(); ++q) {
    const auto& b = yaml.parts[q];
    SCOPED_TRACE(b.name);
    const std::size_t p = static_cast<std::size_t>(deck.part_index(b.name));
    const auto& a = deck.parts[p];
    EXPECT_EQ(a.kind, b.kind);
    for (std::size_t e = 0; e < a.element_count() && a.kind == model::ElementKind::Shell4; ++e)
      EXPECT_TRUE(near(a.thickness_of(e), b.thickness_of(e)));  // *ELEMENT_SHELL_THICKNESS too
    EXPECT_EQ(a.through_thickness_points, b.through_thickness_points);
    EXPECT_TRUE(near(a.hourglass_coefficient, b.hourglass_coefficient));
    EXPECT_EQ(elements(deck, p), elements(yaml, q));
    expect_same_material(deck.materials[static_cast<std::size_t>(a.material)],
                         yaml.materials[static_cast<std::size_t>(b.material)]);
  }
  // held dofs and initial velocities per node
  const auto cd = node_conditions(deck), cy = node_conditions(yaml);
  ASSERT_EQ(cd.size(), cy.size());
  for (auto it = cd.begin(), jt = cy.begin(); it != cd.end(); ++it, ++jt) {
    ASSERT_EQ(it->first, jt->first);
    EXPECT_EQ(it->second.first, jt->second.first);
    expect_same_vec(it->second.second, jt->second.second);
  }
  // rigid bodies, by name
  ASSERT_EQ(deck.rigid_bodies.size(), yaml.rigid_bodies.size());
  for (const auto& b : yaml.rigid_bodies) {
    SCOPED_TRACE(b.name);
    const auto& a = by_name(deck.rigid_bodies, b.name, [](const auto& x) { return x.name; });
    EXPECT_EQ(part_names(deck, a.parts), part_names(yaml, b.parts));
    EXPECT_EQ(keys(deck, a.nodes), keys(yaml, b.nodes));
    expect_same_vec(a.velocity_m_s, b.velocity_m_s);
    expect_same_vec(a.angular_velocity_rad_s, b.angular_velocity_rad_s);
    EXPECT_EQ(a.velocity_at_point, b.velocity_at_point);
    expect_same_vec(a.velocity_point_m, b.velocity_point_m);
    EXPECT_TRUE(near(a.mass_kg, b.mass_kg));
    EXPECT_EQ(a.inertia_given, b.inertia_given);
    for (std::size_t r = 0; r < 3; ++r) expect_same_vec(a.inertia_kg_m2[r], b.inertia_kg_m2[r]);
    EXPECT_EQ(a.centre_given, b.centre_given);
    expect_same_vec(a.centre_m, b.centre_m);
    EXPECT_EQ(a.fixed, b.fixed);
    EXPECT_TRUE(near(a.failure.normal_N, b.failure.normal_N));
    EXPECT_TRUE(near(a.failure.shear_N, b.failure.shear_N));
    EXPECT_EQ(a.failure.exp_n, b.failure.exp_n);
    EXPECT_EQ(a.failure.exp_m, b.failure.exp_m);
    EXPECT_TRUE(near(a.failure.time_s, b.failure.time_s));
  }
  // prescribed motions and loads, in order
  const double end = yaml.controls.end_time_s;
  ASSERT_EQ(deck.prescribed_velocities.size(), yaml.prescribed_velocities.size());
  for (std::size_t k = 0; k < yaml.prescribed_velocities.size(); ++k) {
    const auto &a = deck.prescribed_velocities[k], &b = yaml.prescribed_velocities[k];
    SCOPED_TRACE(b.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(keys(deck, a.nodes), keys(yaml, b.nodes));
    EXPECT_EQ(a.dof, b.dof);
    EXPECT_EQ(
        a.rigid_body < 0 ? "" : deck.rigid_bodies[static_cast<std::size_t>(a.rigid_body)].name,
        b.rigid_body < 0 ? "" : yaml.rigid_bodies[static_cast<std::size_t>(b.rigid_body)].name);
    expect_same_curve(a.velocity, b.velocity, end);
  }
  ASSERT_EQ(deck.loads.size(), yaml.loads.size());
  for (std::size_t k = 0; k < yaml.loads.size(); ++k) {
    const auto &a = deck.loads[k], &b = yaml.loads[k];
    SCOPED_TRACE(b.name);
    EXPECT_EQ(keys(deck, a.nodes), keys(yaml, b.nodes));
    EXPECT_EQ(a.dof, b.dof);
    expect_same_curve(a.force, b.force, end);
  }
  // contacts, by name: slave nodes and faces (derived where not given), masters, options
  ASSERT_EQ(deck.contacts.size(), yaml.contacts.size());
  for (const auto& b : yaml.contacts) {
    SCOPED_TRACE(b.name);
    const auto& a = by_name(deck.contacts, b.name, [](const auto& x) { return x.name; });
    const auto slave_faces = [](const model::Model& m, const model::Contact& c) {
      return c.slave_faces.empty() && c.kind == model::ContactKind::SurfaceToSurface
                 ? contact::slave_faces(m, c.slave_nodes, c.master_parts)
                 : c.slave_faces;
    };
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(keys(deck, a.slave_nodes), keys(yaml, b.slave_nodes));
    EXPECT_EQ(faces(deck, slave_faces(deck, a)), faces(yaml, slave_faces(yaml, b)));
    EXPECT_EQ(part_names(deck, a.master_parts), part_names(yaml, b.master_parts));
    EXPECT_TRUE(near(a.penalty_scale, b.penalty_scale));
    EXPECT_EQ(a.soft, b.soft);
    EXPECT_TRUE(near(a.soft_scale, b.soft_scale));
    EXPECT_EQ(a.static_friction, b.static_friction);
    EXPECT_EQ(a.dynamic_friction, b.dynamic_friction);
    EXPECT_TRUE(near(a.friction_decay_s_m, b.friction_decay_s_m));
    EXPECT_TRUE(near(a.slave_thickness_m, b.slave_thickness_m));
    EXPECT_TRUE(near(a.master_thickness_m, b.master_thickness_m));
  }
  // rigid walls, by name
  ASSERT_EQ(deck.rigid_walls.size(), yaml.rigid_walls.size());
  for (const auto& b : yaml.rigid_walls) {
    SCOPED_TRACE(b.name);
    const auto& a = by_name(deck.rigid_walls, b.name, [](const auto& x) { return x.name; });
    EXPECT_EQ(keys(deck, a.nodes), keys(yaml, b.nodes));
    EXPECT_EQ(a.shape, b.shape);
    expect_same_vec(a.point_m, b.point_m);
    expect_same_vec(a.normal, b.normal);
    expect_same_vec(a.edge, b.edge);
    EXPECT_TRUE(near(a.length_m, b.length_m));
    EXPECT_TRUE(near(a.width_m, b.width_m));
    EXPECT_TRUE(near(a.radius_m, b.radius_m));
    EXPECT_TRUE(near(a.mass_kg, b.mass_kg));
    EXPECT_TRUE(near(a.velocity_m_s, b.velocity_m_s));
  }
  // probes, by name: a node's position or a body's name
  ASSERT_EQ(deck.probes.size(), yaml.probes.size());
  for (const auto& b : yaml.probes) {
    SCOPED_TRACE(b.name);
    const auto& a = by_name(deck.probes, b.name, [](const auto& x) { return x.name; });
    ASSERT_EQ(a.kind, b.kind);
    if (b.kind == model::Probe::Kind::Node) {
      EXPECT_EQ(key(deck, a.index), key(yaml, b.index));
    } else {
      EXPECT_EQ(deck.rigid_bodies[static_cast<std::size_t>(a.index)].name,
                yaml.rigid_bodies[static_cast<std::size_t>(b.index)].name);
    }
  }
  const auto &c = deck.controls, &e = yaml.controls;
  EXPECT_EQ(c.end_time_s, e.end_time_s);
  EXPECT_EQ(c.dt_scale, e.dt_scale);
  EXPECT_EQ(c.history_interval_s, e.history_interval_s);
  EXPECT_EQ(c.field_interval_s, e.field_interval_s);
  EXPECT_EQ(c.bulk_viscosity, e.bulk_viscosity);
  EXPECT_EQ(c.bulk_q_linear, e.bulk_q_linear);
  EXPECT_EQ(c.bulk_q_quadratic, e.bulk_q_quadratic);
  EXPECT_EQ(c.shell_bulk_viscosity, e.shell_bulk_viscosity);
  expect_same_vec(c.gravity_m_s2, e.gravity_m_s2);
  EXPECT_EQ(c.mass_scaling_dt_s, e.mass_scaling_dt_s);
}

// Both run to the end with the same answer: every node's displacement, matched by position,
// within 1e-9 of the largest (the VAD 2 curve's steps and the SI conversions' round-off), and
// the same energies.
TEST(DeckTwin, DeckAndTwinRunTheSame) {
  const model::Model yaml = io::read_scenario(kDir + "twin.yaml");
  const model::Model deck = deck::read_deck(kDir + "main.k", {"mm-t-s", {}}).model;
  integration::Solver a(deck), b(yaml);
  a.initialize();
  b.initialize();
  testing::run_side_by_side(
      a, b, [&] { EXPECT_NEAR(a.time_s(), b.time_s(), 1e-12 * b.time_s() + 1e-300); });
  EXPECT_EQ(a.finished(), b.finished());
  std::map<Key, std::size_t> at;
  for (std::size_t i = 0; i < yaml.nodes.count(); ++i)
    at[key(yaml, static_cast<std::int32_t>(i))] = i;
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < deck.nodes.count(); ++i) {
    const std::size_t j = at.at(key(deck, static_cast<std::int32_t>(i)));
    for (std::size_t d = 0; d < 3; ++d) {
      scale = std::max(scale, std::abs(b.displacement()[3 * j + d]));
      diff = std::max(diff, std::abs(a.displacement()[3 * i + d] - b.displacement()[3 * j + d]));
    }
  }
  std::printf(
      "[measured] twin deck and YAML after %.3e s: max |du| %.2e of %.2e m; total "
      "energy %.9e / %.9e J, external work %.9e / %.9e J\n",
      a.time_s(), diff, scale, a.energy().total_J(), b.energy().total_J(),
      a.energy().external_work_J, b.energy().external_work_J);
  EXPECT_GT(scale, 1e-6);
  EXPECT_LE(diff, 1e-9 * scale);
  EXPECT_TRUE(near(a.energy().total_J(), b.energy().total_J(), 1e-9));
  EXPECT_TRUE(near(a.energy().external_work_J, b.energy().external_work_J, 1e-5));
}

/// The keywords in the twin's three files, as written (suffixes and format marks dropped).
std::set<std::string> keywords_used() {
  std::set<std::string> out;
  for (const char* f : {"main.k", "mesh_long.k", "props/props_free.k"}) {
    std::ifstream in(kDir + f);
    std::string line;
    while (std::getline(in, line))
      if (!line.empty() && line[0] == '*') {
        std::string k = line.substr(0, line.find_first_of(" \t\r+"));
        std::transform(k.begin(), k.end(), k.begin(), ::toupper);
        out.insert(k);
      }
  }
  return out;
}

// Every keyword the reader supports is in the twin (the numbered *MAT_0xx aliases read as their
// named forms; *DATABASE_* as the ones it reads and one it accepts without effect), in each of
// the three formats at least one keyword.
TEST(DeckTwin, UsesEverySupportedKeyword) {
  const auto used = keywords_used();
  const auto has = [&](const std::string& k) {
    for (const auto& u : used) {
      if (u == k) return true;
      // the _TITLE / _ID forms of k
      if (u.rfind(k, 0) == 0 &&
          (u.substr(k.size()) == "_TITLE" || u.substr(k.size()) == "_ID" ||
           u.substr(k.size()) == "_ID_TITLE" || u.substr(k.size()) == "_TITLE_ID"))
        return true;
    }
    return false;
  };
  std::vector<std::string> missing;
  for (std::string k : deck::supported_keywords()) {
    k = k.substr(0, k.find('('));
    if (std::regex_match(k, std::regex(R"(\*MAT_0\d\d)"))) continue;
    if (k == "*CONTROL_MPP_*") {
      if (!has("*CONTROL_MPP_DECOMPOSITION_AUTOMATIC"))
        missing.push_back("*CONTROL_MPP_DECOMPOSITION_AUTOMATIC");
      continue;
    }
    if (k == "*SENSOR_DEFINE_*") {
      if (!has("*SENSOR_DEFINE_NODE")) missing.push_back("*SENSOR_DEFINE_NODE");
      continue;
    }
    if (k == "*DATABASE_*") {
      for (const char* d :
           {"*DATABASE_GLSTAT", "*DATABASE_BINARY_D3PLOT", "*DATABASE_HISTORY_NODE_ID",
            "*DATABASE_RBDOUT", "*DATABASE_EXTENT_BINARY"})
        if (!has(d)) missing.push_back(d);
      continue;
    }
    if (!has(k)) missing.push_back(k);
  }
  std::string list;
  for (const auto& k : missing) list += " " + k;
  EXPECT_TRUE(missing.empty()) << "not in the twin deck:" << list;
  std::ifstream long_file(kDir + "mesh_long.k");
  std::stringstream s;
  s << long_file.rdbuf();
  EXPECT_NE(s.str().find("*KEYWORD LONG=Y"), std::string::npos);
}

// Twenty-four mistakes in the twin, each in one of its three files: `crashlink run` names the file
// and line, the keyword, the field and its columns, says what is wrong and the fix, exits 2, and
// runs nothing (no result.h5).
// Mistakes in the twin (26), each one edit of one of its three files: `crashlink run` names the
// file and line (found here from the edited text), the keyword, the field and its columns, says
// what is wrong and the fix, exits 2, and runs nothing (no result.h5).
TEST(DeckTwin, MistakesExitTwoWithTheirFileAndLineAndNothingRun) {
  struct Mistake {
    const char* file;     ///< the file edited
    const char* find;     ///< the text replaced (its first occurrence)
    const char* replace;  ///< by this
    const char* at_file;  ///< the file the message names
    const char* at_text;  ///< in it, after the edit: the message's line is this text's last line
    const char* message;  ///< what follows "file:line: "
  };
  const Mistake mistakes[] = {
      {"main.k", "      10       2     101     102     105     104",
       "      10       2     999     102     105     104", "main.k", "      10       2     999",
       "*ELEMENT_SHELL field N1 (columns 17-24) = 999: node 999 is not defined"},
      {"main.k", "      11       2     102     103     106     105",
       "      10       2     102     103     106     105", "main.k",
       "      10       2     102     103",
       "*ELEMENT_SHELL field EID (columns 1-8) = 10: *ELEMENT_SHELL 10 is already defined"},
      {"main.k", "     &tend", "    &tende", "main.k", "    &tende",
       "*CONTROL_TERMINATION field ENDTIM (columns 1-10) = &tende: parameter 'tende' is not "
       "defined"},
      {"props/props_free.k", "plate\n2,2,2", "plate\n2,2,9", "props/props_free.k", "2,2,9",
       "*PART field MID (columns 5-5) = 9: material 9 is not defined"},
      {"props/props_free.k", "strip\n3,3,3", "strip\n3,8,3", "props/props_free.k", "3,8,3",
       "*PART field SECID (columns 3-3) = 8: section 8 is not defined"},
      {"props/props_free.k", "0.1,250.0", "0.6,250.0", "props/props_free.k", "0.5,300.0",
       "*DEFINE_CURVE field A (columns 1-3) = 0.5: abscissae must increase: 0.5 follows 0.6"},
      {"props/props_free.k", "3,1,3,3", "3,1,3,77", "props/props_free.k", "3,1,3,77",
       "*CONTACT_NODES_TO_SURFACE field MSTYP (columns 7-8) = 77: surface type 77 is not read"},
      {"props/props_free.k", "10.0,0.0,12.0,5.0,6.0", "0.0,0.0,13.0,5.0,6.0", "props/props_free.k",
       "0.0,0.0,13.0,5.0,6.0",
       "*RIGIDWALL_GEOMETRIC_FLAT_ID field XHEV (columns 1-3) = 0.0: the edge l from the tail (0, "
       "0, 12) to (XHEV, YHEV, ZHEV) must be a vector in the wall's plane"},
      {"props/props_free.k", "5.0,40.0", "0.0,40.0", "props/props_free.k", "0.0,40.0",
       "*RIGIDWALL_GEOMETRIC_CYLINDER_ID field RADCYL (columns 1-3) = 0.0: the cylinder needs its "
       "radius (> 0)"},
      {"props/props_free.k", "-10.0,10.0,8.0,30.0,10.0,8.0", "-10.0,10.0,8.0,-10.0,10.0,8.0",
       "props/props_free.k", "-10.0,10.0,8.0,-10.0",
       "*RIGIDWALL_GEOMETRIC_CYLINDER_ID field XH (columns 16-20) = -10.0: the head point is the "
       "tail point"},
      {"props/props_free.k", "8,5,2,10", "8,5,1,10", "props/props_free.k", "8,5,1,10",
       "*BOUNDARY_PRESCRIBED_MOTION_SET field VAD (columns 5-5) = 1: crashlink prescribes a "
       "velocity (VAD 0) or a displacement"},
      {"props/props_free.k", "4,1,0,11", "2,1,0,11", "props/props_free.k", "2,1,0,11",
       "*BOUNDARY_PRESCRIBED_MOTION_RIGID field PID (columns 1-1) = 2: part 2 is not a rigid part"},
      {"props/props_free.k", "4,&rhost,&estee,0.3\n1.0,0,7", "4,&rhost,&estee,0.3\n1.0,0,9",
       "props/props_free.k", "1.0,0,9", "*MAT_RIGID field CON2 (columns 7-7) = 9: must be 0 to 7"},
      {"props/props_free.k", "*SET_SHELL_LIST\n11\n11", "*SET_SHELL_LIST\n11\n99",
       "props/props_free.k", "*SET_SHELL_LIST\n11\n99",
       "*SET_SHELL_LIST field ID1 (columns 1-10) = 99: shell 99 is not defined"},
      {"props/props_free.k", "101,102,105,104", "101,102,106,104", "props/props_free.k",
       "101,102,106,104", "*SET_SEGMENT field N1 (columns 1-3) = 101: is not a face of an element"},
      {"main.k", "*CONTROL_SHELL", "*CONTROL_SOLID", "main.k", "*CONTROL_SOLID",
       "*CONTROL_SOLID: not supported; fix: remove it, or pass --ignore CONTROL_SOLID"},
      {"main.k", "         4         1         4\n", "         4         1         1\n", "main.k",
       "      55.0       5.0       5.0      0.01",
       "*PART_INERTIA field TM (columns 31-40) = 0.01: crashlink reads *PART_INERTIA on rigid "
       "parts (*MAT_RIGID) only"},
      {"mesh_long.k", "                 312", "                 311", "mesh_long.k",
       "                 311           72.0",
       "*NODE field NID (columns 1-20) = 311: node 311 is already defined at mesh_long.k:"},
      {"main.k", "         2         5    1500.0", "         2         2    1500.0", "main.k",
       "         2         2    1500.0",
       "*CONSTRAINED_SPOTWELD_ID field N2 (columns 11-20) = 2: is N1"},
      {"props/props_free.k", "0.3,0.2,0.01", "0.3,0.2x,0.01", "props/props_free.k", "0.3,0.2x,0.01",
       "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID field FD (columns 5-8) = 0.2x: not a number"},
      {"props/props_free.k", "14\n105,106", "14\n105,106,107", "main.k",
       "        14         0         0",
       "*CONSTRAINED_GENERALIZED_WELD_SPOT_ID field NSID (columns 1-10) = 14: node set 14 holds 3 "
       "nodes"},
      {"main.k", "*SENSOR_DEFINE_NODE", "*SENSOR_SWITCH", "main.k", "*SENSOR_SWITCH",
       "*SENSOR_SWITCH: a sensor that switches something"},
      {"main.k", "*INCLUDE\nprops_free.k", "*INCLUDE\nprops_fre.k", "main.k",
       "*INCLUDE\nprops_fre.k",
       "*INCLUDE field FILENAME (columns 1-80) = props_fre.k: no such file (looked for "
       "props_fre.k, props/props_fre.k, ./props_fre.k)"},
      {"main.k", "R estee   210.0*1000.0", "R estee   210.0*1.0e9", "props/props_free.k",
       "1,&rhost,&estee,0.3",
       "*MAT_ELASTIC_TITLE field E (columns 10-15) = &estee: with RO = 7.85e-09 and --units "
       "mm-t-s, the wave speed sqrt(E/RO) is 5.172e+06 m/s"},
      {"main.k", "      35.0       5.0      60.0     0.002",
       "      35.0       5.0      60.0    -0.002", "main.k",
       "      35.0       5.0      60.0    -0.002",
       "*CONSTRAINED_NODAL_RIGID_BODY_INERTIA field TM (columns 31-40) = -0.002: the body's mass "
       "must be > 0"},
      {"props/props_free.k", "4,1,0,11", "4,6,0,11", "props/props_free.k", "4,6,0,11",
       "*BOUNDARY_PRESCRIBED_MOTION_RIGID field DOF (columns 3-3) = 6: rigid body 'block' (part 4) "
       "already holds this dof"},
  };
  const std::string crashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink";
  const auto root = std::filesystem::temp_directory_path() /
                    ("crashlink_twin_mistakes_" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  int k = 0;
  for (const auto& m : mistakes) {
    SCOPED_TRACE(m.message);
    const auto dir = root / std::to_string(k++);
    std::filesystem::create_directories(dir);
    std::filesystem::copy(kDir, dir, std::filesystem::copy_options::recursive);
    const auto path = dir / m.file;
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    std::string s = text.str();
    const auto at = s.find(m.find);
    ASSERT_NE(at, std::string::npos) << m.find;
    s.replace(at, std::string(m.find).size(), m.replace);
    std::ofstream(path, std::ios::trunc) << s;
    int status = 0;
    std::string out = testing::run_command(crashlink + " run " + (dir / "main.k").string() +
                                               " --units mm-t-s --out " + (dir / "out").string(),
                                           status);
    for (auto p = out.find(dir.string() + "/"); p != std::string::npos;
         p = out.find(dir.string() + "/"))
      out.erase(p, dir.string().size() + 1);
    // the line of at_text's last line in the edited at_file
    std::stringstream edited;
    edited << std::ifstream(dir / m.at_file).rdbuf();
    const std::string t = edited.str(), marker = m.at_text;
    const auto pos = t.find(marker);
    ASSERT_NE(pos, std::string::npos) << m.at_text;
    const auto line = 1 +
                      std::count(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(pos), '\n') +
                      std::count(marker.begin(), marker.end(), '\n');
    const std::string expected =
        fmt::format("crashlink: input error: {}:{}: {}", m.at_file, line, m.message);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << out;
    EXPECT_NE(out.find(expected), std::string::npos) << expected << "\n" << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "result.h5")) << "nothing runs";
  }
  EXPECT_GE(k, 26);
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace crashlink
