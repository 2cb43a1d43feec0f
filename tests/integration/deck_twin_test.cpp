// The twin deck (tests/data/decks/twin/main.k: fixed, long and free format in three files joined
// by *INCLUDE, with *PARAMETERs, in mm-t-s) gives the model of its YAML twin (twin.yaml, SI,
// crashlink's generators): the same node positions, elements (corners in the same order),
// sections, materials in SI, constraints, initial velocities, rigid body and controls. The deck
// numbers its nodes itself, so everything is compared by position.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "solver/deck/model_from_deck.h"
#include "solver/io/scenario_reader.h"

namespace crashlink {
namespace {

const std::string kDir = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/twin/";

/// A node's position rounded to 1 nm, as a key.
using Key = std::array<long long, 3>;
Key key(const model::Model& m, std::int32_t i) {
  const auto k = static_cast<std::size_t>(i);
  return {std::llround(m.nodes.x0[3 * k] * 1e9), std::llround(m.nodes.x0[3 * k + 1] * 1e9),
          std::llround(m.nodes.x0[3 * k + 2] * 1e9)};
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

/// Per node position: its fixed dofs and initial velocity.
std::map<Key, std::pair<int, Vec3>> node_conditions(const model::Model& m) {
  std::map<Key, std::pair<int, Vec3>> out;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    out[key(m, static_cast<std::int32_t>(i))] = {m.fixed[i], Vec3{}};
  for (const auto& iv : m.initial_velocities)
    for (auto i : iv.nodes) out[key(m, i)].second = iv.velocity_m_s;
  return out;
}

void expect_same_material(const materials::Material& a, const materials::Material& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_NEAR(a.density_kg_m3, b.density_kg_m3, 1e-9 * b.density_kg_m3);
  EXPECT_NEAR(a.youngs_modulus_Pa, b.youngs_modulus_Pa, 1e-9 * b.youngs_modulus_Pa);
  EXPECT_DOUBLE_EQ(a.poisson_ratio, b.poisson_ratio);
  ASSERT_EQ(a.hardening.eps_p.size(), b.hardening.eps_p.size());
  for (std::size_t i = 0; i < a.hardening.eps_p.size(); ++i) {
    EXPECT_NEAR(a.hardening.eps_p[i], b.hardening.eps_p[i], 1e-12);
    EXPECT_NEAR(a.hardening.sigma_y_Pa[i], b.hardening.sigma_y_Pa[i],
                1e-9 * b.hardening.sigma_y_Pa[i]);
  }
}

TEST(DeckTwin, DeckGivesTheModelOfItsYamlTwin) {
  const model::Model yaml = io::read_scenario(kDir + "twin.yaml");
  const model::Model deck = deck::read_deck(kDir + "main.k", {"mm-t-s", {}}).model;
  EXPECT_EQ(deck.name, yaml.name);
  ASSERT_EQ(deck.nodes.count(), yaml.nodes.count());
  ASSERT_EQ(deck.parts.size(), yaml.parts.size());
  for (std::size_t p = 0; p < yaml.parts.size(); ++p) {
    SCOPED_TRACE(yaml.parts[p].name);
    const auto& a = deck.parts[p];
    const auto& b = yaml.parts[p];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_DOUBLE_EQ(a.thickness_m, b.thickness_m);
    EXPECT_EQ(a.through_thickness_points, b.through_thickness_points);
    EXPECT_DOUBLE_EQ(a.hourglass_coefficient, b.hourglass_coefficient);
    EXPECT_EQ(elements(deck, p), elements(yaml, p));
    expect_same_material(deck.materials[static_cast<std::size_t>(a.material)],
                         yaml.materials[static_cast<std::size_t>(b.material)]);
  }
  const auto cd = node_conditions(deck), cy = node_conditions(yaml);
  ASSERT_EQ(cd.size(), cy.size());
  for (auto it = cd.begin(), jt = cy.begin(); it != cd.end(); ++it, ++jt) {
    EXPECT_EQ(it->first, jt->first);
    EXPECT_EQ(it->second.first, jt->second.first);
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_DOUBLE_EQ(it->second.second[c], jt->second.second[c]);
  }
  ASSERT_EQ(deck.rigid_bodies.size(), yaml.rigid_bodies.size());
  EXPECT_EQ(deck.rigid_bodies[0].parts, yaml.rigid_bodies[0].parts);
  for (std::size_t c = 0; c < 3; ++c)
    EXPECT_DOUBLE_EQ(deck.rigid_bodies[0].velocity_m_s[c], yaml.rigid_bodies[0].velocity_m_s[c]);
  EXPECT_DOUBLE_EQ(deck.controls.end_time_s, yaml.controls.end_time_s);
  EXPECT_DOUBLE_EQ(deck.controls.dt_scale, yaml.controls.dt_scale);
  EXPECT_DOUBLE_EQ(deck.controls.history_interval_s, yaml.controls.history_interval_s);
}

}  // namespace
}  // namespace crashlink
