// Conventional mass scaling (integration/mass_scaling.h, a deck's *CONTROL_TIMESTEP DT2MS < 0):
// the two-rate bar deck (10 mm cubes on one half, 5 mm long hexes on the other) scaled to the
// coarse half's step. Every fine element gets the density that brings its step there, and nothing
// else does; the added mass is sum m_e ((dt_target / dt_e)^2 - 1); the run then takes TSSFAC x
// dt_target, 1.6 x fewer steps, with its energy balance kept; the deck's reading says what was
// added; the YAML's `mass_scaling_dt` does the same.
#include "solver/integration/mass_scaling.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/deck/model_from_deck.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/run_helpers.h"
#include "tests/integration/shell_command.h"

namespace crashlink {
namespace {

const std::string kDir = std::string(CRASHLINK_TEST_DATA_DIR) + "/data/decks/two_rates/";

/// The two-rate deck with DT2MS written into its *CONTROL_TIMESTEP, in a folder of its own.
std::string deck_with_dt2ms(double dt2ms_s, const std::filesystem::path& dir) {
  std::ifstream in(kDir + "two_rates.k");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string card = "*CONTROL_TIMESTEP\n                 0.9\n";
  const auto at = s.find(card);
  EXPECT_NE(at, std::string::npos);
  // free format: DT2MS to the digit
  const std::string line = "*CONTROL_TIMESTEP\n,0.9,,," + fmt::format("{:.17g}", dt2ms_s) + "\n";
  s.replace(at, card.size(), line);
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kDir + "bar_nodes.k", dir / "bar_nodes.k",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "two_rates.k") << s;
  return (dir / "two_rates.k").string();
}

TEST(MassScaling, FineHalfScaledToTheCoarseStep) {
  const model::Model plain = deck::read_deck(kDir + "two_rates.k", {"mm-t-s", {}}).model;
  integration::Solver s0(plain);
  s0.record_element_steps(true);
  s0.initialize();
  ASSERT_EQ(plain.parts.size(), 2u);
  const auto& dt_coarse = s0.parts()[0].element_dt_s;
  const auto& dt_fine = s0.parts()[1].element_dt_s;
  const double target = *std::min_element(dt_coarse.begin(), dt_coarse.end());
  // 10 mm cubes against 5 x 10 x 10 mm hexes: a step 1.6 x longer
  const double fine_min = *std::min_element(dt_fine.begin(), dt_fine.end());
  std::printf("coarse steps %.4e - %.4e s, fine %.4e - %.4e s\n", target,
              *std::max_element(dt_coarse.begin(), dt_coarse.end()), fine_min,
              *std::max_element(dt_fine.begin(), dt_fine.end()));
  EXPECT_GT(target, 1.5 * fine_min);

  // DT2MS in ms (the deck is in mm-t-s: seconds) a hair above the coarse step's minimum, so
  // that the coarse elements stay as they are
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_mass_scaling_" + std::to_string(::getpid()));
  const double dt2ms = -target * (1.0 - 1e-9);
  const deck::DeckRead r = deck::read_deck(deck_with_dt2ms(dt2ms, dir), {"mm-t-s", {}});
  const model::Model& m = r.model;
  EXPECT_DOUBLE_EQ(m.controls.mass_scaling_dt_s, -dt2ms);
  EXPECT_TRUE(m.parts[0].element_density_scale.empty()) << "the coarse half keeps its density";
  ASSERT_EQ(m.parts[1].element_density_scale.size(), m.parts[1].element_count());
  // the added mass, element by element: m_e ((dt_target / dt_e)^2 - 1), m_e = rho V_e
  const double rho = m.materials[0].density_kg_m3;
  double added = 0.0;
  for (std::size_t e = 0; e < dt_fine.size(); ++e) {
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};  // the element is a box
    for (int k = 0; k < 8; ++k)
      for (std::size_t d = 0; d < 3; ++d) {
        const double x =
            m.nodes.x0[3 * static_cast<std::size_t>(
                               m.parts[1].connectivity[8 * e + static_cast<std::size_t>(k)]) +
                       d];
        lo[d] = std::min(lo[d], x);
        hi[d] = std::max(hi[d], x);
      }
    const double v_e = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    const double s = std::max(1.0, (-dt2ms / dt_fine[e]) * (-dt2ms / dt_fine[e]));
    EXPECT_NEAR(m.parts[1].element_density_scale[e], std::max(s, 1.0), 1e-12 * s);
    added += rho * v_e * (s - 1.0);
  }
  bool said = false;
  for (const auto& msg : r.messages) {
    said = said || msg.find("deformable elements scaled") != std::string::npos;
    if (msg.find("mass scaling to a stable step") != std::string::npos)
      std::printf("[deck] %s\n", msg.c_str());
  }
  EXPECT_TRUE(said) << "the reading reports the mass added";

  integration::Solver s1(m);
  s1.initialize();
  EXPECT_NEAR(s1.total_mass_kg() - s0.total_mass_kg(), added, 1e-9 * added);
  EXPECT_NEAR(s1.dt_s(), 0.9 * -dt2ms, 1e-9 * s1.dt_s()) << "the run takes TSSFAC x |DT2MS|";
  EXPECT_NEAR(s1.dt_s() / s0.dt_s(), target / *std::min_element(dt_fine.begin(), dt_fine.end()),
              1e-6);
  // the scaled run: fewer cycles, the energy balance kept
  integration::Solver run(m);
  std::size_t cycles = 0;
  testing::run(run, [&](const integration::Solver&) { ++cycles; });
  const auto& e = run.energy();
  std::printf(
      "[measured] mass scaling: %zu cycles (unscaled %d), added %.4g kg of %.4g kg, "
      "balance %.2e of E0\n",
      cycles, static_cast<int>(m.controls.end_time_s / s0.dt_s()), added, s0.total_mass_kg(),
      e.balance_J() / e.initial_total_J);
  EXPECT_LT(std::abs(e.balance_J()), 1e-3 * e.initial_total_J);
  EXPECT_NEAR(static_cast<double>(cycles), m.controls.end_time_s / s1.dt_s(), 10.0);
  std::filesystem::remove_all(dir);
}

TEST(MassScaling, PositiveDt2msIsRefusedAtItsField) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_mass_scaling_pos_" + std::to_string(::getpid()));
  const std::string deck = deck_with_dt2ms(1e-7, dir);
  std::string msg;
  try {
    (void)deck::read_deck(deck, {"mm-t-s", {}});
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_NE(
      msg.find(":50: *CONTROL_TIMESTEP field DT2MS (columns 8-29) = 9.9999999999999995e-08: a "
               "positive DT2MS"),
      std::string::npos)
      << msg;
  std::filesystem::remove_all(dir);
}

// A YAML scene: `controls: {mass_scaling_dt: ...}` scales the part whose shells are below it; a
// target at or above the end time is refused.
TEST(MassScaling, YamlKeyScalesTheFinePlate) {
  const std::string yaml = R"(name: two plates
controls: {end_time: 1.0e-5, mass_scaling_dt: 1.2e-6}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  coarse: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.1, 0.1], normal: z, divisions: [10, 10]}}
  fine: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0.2, 0, 0], size: [0.1, 0.1], normal: z, divisions: [20, 20]}}
)";
  const model::Model m = io::parse_scenario(yaml, "two_plates.yaml");
  EXPECT_DOUBLE_EQ(m.controls.mass_scaling_dt_s, 1.2e-6);
  // L_e = A / diagonal = a / sqrt(2), c = 5422 m/s: 10 mm shells 1.304e-6 s, above; 5 mm ones
  // 0.652e-6 s, below: (1.2 / 0.652)^2 = 3.39
  EXPECT_TRUE(m.parts[0].element_density_scale.empty());
  ASSERT_EQ(m.parts[1].element_density_scale.size(), 400u);
  for (double f : m.parts[1].element_density_scale) EXPECT_NEAR(f, 3.39, 0.01);
  integration::Solver s(m);
  s.initialize();
  EXPECT_NEAR(s.dt_s(), 0.9 * 1.2e-6, 1e-9 * s.dt_s());
  const auto r = integration::describe_mass_scaling(m);
  EXPECT_EQ(r.scaled_elements, 400u);
  EXPECT_EQ(r.deformable_elements, 500u);
  // the fine plate's 7850 x 0.1 x 0.1 x 0.001 = 0.0785 kg, x (3.39 - 1)
  EXPECT_NEAR(r.added_mass_kg, 0.0785 * 2.39, 0.0785 * 0.02);
  std::string msg;
  try {
    std::string slip = yaml;
    slip.replace(slip.find("mass_scaling_dt: 1.2e-6"), 23, "mass_scaling_dt: 1.2e-3");
    (void)io::parse_scenario(slip, "slip.yaml");
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("slip.yaml:2: controls.mass_scaling_dt: mass scaling to a stable step of "
                     "0.0012 s, at or above the end time 1e-05 s"),
            std::string::npos)
      << msg;
}

// A contact's nodal masses are the scaled ones: a plate of equal 5 mm shells, all scaled alike,
// over a rigid one: the run takes the scaled step, which the contact's springs would bound with
// the unscaled masses.
TEST(MassScaling, ContactStepBoundTakesTheScaledMasses) {
  const auto scene = [](double dt_ms, bool contact) {
    std::string y = fmt::format(R"(name: stacked
controls: {{end_time: 1.0e-5, mass_scaling_dt: {}}}
materials:
  steel: {{type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}}
  block: {{type: rigid, density: 7850.0}}
parts:
  lower: {{material: block, element: shell4, thickness: 1.0e-3, mesh: {{generator: plate, origin: [0, 0, 0], size: [0.1, 0.1], normal: z, divisions: [20, 20]}}}}
  upper: {{material: steel, element: shell4, thickness: 1.0e-3, mesh: {{generator: plate, origin: [0, 0, 0.002], size: [0.1, 0.1], normal: z, divisions: [20, 20]}}}}
rigid_bodies:
  anvil: {{parts: [lower], mass: 10.0, inertia: [1.0, 1.0, 1.0]}}
)",
                                dt_ms);
    if (contact) y += "contacts:\n  plates: {slave: {part: upper}, master: lower}\n";
    const model::Model m = io::parse_scenario(y, "stacked.yaml");
    integration::Solver s(m);
    s.initialize();
    return s.dt_s();
  };
  const double free0 = scene(0.0, false), dt0 = scene(0.0, true), dt1 = scene(1.2e-6, true);
  std::printf(
      "[measured] stacked plates: element step %.4e s, with the contact %.4e s, scaled "
      "%.4e s\n",
      free0, dt0, dt1);
  // every element at the same step: all scaled to 1.2e-6 s, and the contact, whose springs
  // between the plate and the rigid one bound the step by their nodal masses, lets the run take
  // it (with the unscaled masses it held the run near the unscaled step)
  EXPECT_NEAR(dt1, 0.9 * 1.2e-6, 1e-9 * dt1);
  EXPECT_GT(dt1, 1.5 * dt0);
}

// `crashlink run` says what the scaling added before a YAML scene runs.
TEST(MassScaling, RunReportsTheAddedMass) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_mass_scaling_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "p.yaml") << R"(name: plate
controls: {end_time: 2.0e-6, mass_scaling_dt: 1.0e-6}
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  plate: {material: steel, element: shell4, thickness: 1.0e-3, mesh: {generator: plate, origin: [0, 0, 0], size: [0.05, 0.05], normal: z, divisions: [10, 10]}}
)";
  int status = 0;
  const std::string out = testing::run_command(
      std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " + (dir / "p.yaml").string() +
          " --out " + (dir / "out").string() + " 2>&1",
      status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  // 5 mm shells step 0.652e-6 s: (1 / 0.652)^2 = 2.35, the plate's 19.6 g x 1.35 added
  EXPECT_NE(out.find("crashlink run: mass scaling to a stable step of 1e-06 s (safety factor not "
                     "included): 100 of 100 deformable elements scaled, 0.02"),
            std::string::npos)
      << out;
  std::filesystem::remove_all(dir);
}

// A scenario naming a deck with DT2MS sets the mass scaling once, its own controls first: 0
// turns it off, another step replaces the deck's.
TEST(MassScaling, ScenarioOverridesTheDecksDt2ms) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_mass_scaling_over_" + std::to_string(::getpid()));
  (void)deck_with_dt2ms(-1.0e-6, dir);
  const auto with = [&](const std::string& controls) {
    std::ofstream(dir / "s.yaml") << "model: {deck: two_rates.k, units: mm-t-s}\n" + controls;
    return io::read_scenario((dir / "s.yaml").string());
  };
  const model::Model deck_only = with("");
  EXPECT_DOUBLE_EQ(deck_only.controls.mass_scaling_dt_s, 1.0e-6);
  EXPECT_FALSE(deck_only.parts[1].element_density_scale.empty());
  const model::Model off = with("controls: {mass_scaling_dt: 0.0}\n");
  for (const auto& p : off.parts) EXPECT_TRUE(p.element_density_scale.empty()) << p.name;
  const model::Model more = with("controls: {mass_scaling_dt: 2.0e-6}\n");
  integration::Solver s(more);
  s.initialize();
  EXPECT_NEAR(s.dt_s(), 0.9 * 2.0e-6, 1e-9 * s.dt_s()) << "both halves scaled to 2 us";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace crashlink
