// The daemon's side of `paper` (solver/daemon/paper_port.h) without sockets: the coupled nodes it
// registers, its checks of the coordinator's Setup (sizes, [11] roles, summed masses [5] against
// its own cut), the solver it rebuilds when the Setup's masses differ in a bit, and the
// FreeState / Correction conversions.
#include "solver/daemon/paper_port.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "solver/cosim/paper_runner.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "tests/integration/process_test_support.h"
#include "transport/errors.h"

using namespace crashlink;

namespace {

/// The model of a scenario text (through a temporary file, as the daemon reads it).
model::Model read_yaml(const std::string& yaml) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("crashlink-paper-port-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << yaml;
  auto m = io::read_scenario(path.string());
  std::filesystem::remove(path);
  return m;
}

/// bar2 of the process tests: hex parts "fine" [0, 0.2] m (10 mm) and "coarse" [0.2, 0.6] m
/// (40 mm), one domain each: the four nodes at x = 0.2 are the link ([3]-[4]), the coarse domain
/// their [11] reference.
model::Model bar() {
  return read_yaml(proc_test::bar_yaml(1.0e-4));
}

wire::Setup setup_for(const daemon::PaperPort& port) {
  wire::Setup s;
  for (std::size_t j = 0; j < port.nodes.size(); ++j) {
    s.add_summed_masses_kg(port.summed_mass_kg[j]);
    s.add_node_roles(port.nodes[j].reference ? wire::NODE_ROLE_REFERENCE
                                             : wire::NODE_ROLE_NON_REFERENCE);
  }
  return s;
}

std::string thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const ProtocolError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(PaperPort, RegistersTheLinkWithItsPartialMasses) {
  const auto m = bar();
  const auto dec = partition::decompose(m, partition::Scheme::Paper);
  const auto fine = daemon::build_paper_port(dec, "fine");
  const auto coarse = daemon::build_paper_port(dec, "coarse");
  ASSERT_EQ(fine.nodes.size(), 4u);  // the four corners of the cut at x = 0.2
  ASSERT_EQ(coarse.nodes.size(), 4u);
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(fine.nodes[j].global, coarse.nodes[j].global);  // the same order on both sides
    EXPECT_FALSE(fine.nodes[j].reference);  // the larger-step domain is [11]'s reference
    EXPECT_TRUE(coarse.nodes[j].reference);
    // [5]: M = m_fine + m_coarse, the cut's natural mass of the node.
    EXPECT_NEAR(fine.own_mass_kg[j] + coarse.own_mass_kg[j], fine.summed_mass_kg[j],
                1e-12 * fine.summed_mass_kg[j]);
    EXPECT_GT(fine.own_mass_kg[j], 0.0);
    EXPECT_GT(coarse.own_mass_kg[j], fine.own_mass_kg[j]);  // 40 mm elements against 10 mm
  }
  EXPECT_THROW(daemon::build_paper_port(dec, "nowhere"), ModelError);
}

TEST(PaperPort, SetupMassesAndRolesAreChecked) {
  const auto m = bar();
  const auto dec = partition::decompose(m, partition::Scheme::Paper);
  auto port = daemon::build_paper_port(dec, "fine");
  const double M0 = port.summed_mass_kg[0];

  // The same bits: the solver stays.
  EXPECT_EQ(daemon::use_summed_masses(port, setup_for(port), "fine"), nullptr);

  // A last-bit difference (another summation order): a new solver, integrating with the Setup's M.
  auto s = setup_for(port);
  const double M1 = std::nextafter(M0, 2.0 * M0);
  s.set_summed_masses_kg(0, M1);
  auto fresh = daemon::use_summed_masses(port, s, "fine");
  ASSERT_NE(fresh, nullptr);
  fresh->initialize();
  EXPECT_EQ(fresh->mass()[port.nodes[0].local], M1);
  EXPECT_EQ(port.summed_mass_kg[0], M1);

  // A mass that is not the node's natural one, a role the cut does not give, a size: refused.
  s = setup_for(port);
  s.set_summed_masses_kg(1, 1.000001 * port.summed_mass_kg[1]);
  EXPECT_TRUE(has(thrown([&] { daemon::use_summed_masses(port, s, "fine"); }), "natural mass"));
  s = setup_for(port);
  s.set_node_roles(2, wire::NODE_ROLE_REFERENCE);
  EXPECT_TRUE(has(thrown([&] { daemon::use_summed_masses(port, s, "fine"); }),
                  "this domain's cut makes it the non-reference side"));
  s = setup_for(port);
  s.mutable_summed_masses_kg()->RemoveLast();
  EXPECT_TRUE(has(thrown([&] { daemon::use_summed_masses(port, s, "fine"); }), "3 summed masses"));
}

TEST(PaperPort, FreeStateAndCorrection) {
  const auto m = bar();
  const auto dec = partition::decompose(m, partition::Scheme::Paper);
  auto port = daemon::build_paper_port(dec, "coarse");
  port.solver->initialize();
  wire::Envelope e;
  wire::EnergyTerms energy;
  energy.set_kinetic_j(1.5);
  daemon::fill_free_state(port, 0, 123, energy, -1, e);
  daemon::fill_free_state(port, 0, 123, energy, -1, e);  // refilled, not appended
  const auto& f = e.free_state();
  EXPECT_EQ(f.accelerations_m_s2_size(), 12);
  EXPECT_EQ(f.displacements_m_size(), 12);
  EXPECT_EQ(f.velocities_m_s_size(), 12);
  EXPECT_EQ(f.stable_step_ticks(), 123);
  EXPECT_EQ(f.energy_time_ticks(), -1);
  EXPECT_EQ(f.energy().kinetic_j(), 1.5);

  // The corrected acceleration lands on the node; the implied force counts as coupling work
  // (Solver::set_acceleration) once the node moves.
  wire::Correction c;
  for (int i = 0; i < 12; ++i) c.add_accelerations_m_s2(i == 0 ? 10.0 : 0.0);
  daemon::apply_correction(port, c, "coarse");
  EXPECT_EQ(port.solver->acceleration()[3 * port.nodes[0].local], 10.0);

  c.mutable_accelerations_m_s2()->RemoveLast();
  EXPECT_TRUE(
      has(thrown([&] { daemon::apply_correction(port, c, "coarse"); }), "11 accelerations"));
  c.add_accelerations_m_s2(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(has(thrown([&] { daemon::apply_correction(port, c, "coarse"); }), "nan"));
}

// A shell plate cut along a line: the nodes on the cut carry rotations in both domains, which
// `paper` cannot couple (translations only); both the daemon and the in-process runner refuse it
// naming the node, the two domains and the fix.
TEST(PaperPort, ShellNodesRotatingOnBothSidesAreRefused) {
  const auto m = read_yaml(proc_test::plate_yaml(1.0e-4));  // domains left | right
  const auto dec = partition::decompose(m, partition::Scheme::Paper);
  try {
    (void)daemon::build_paper_port(dec, "left");
    ADD_FAILURE() << "a shell node rotating on both sides was accepted";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(has(what, "carries rotations in domains 'left' and 'right'")) << what;
    EXPECT_TRUE(has(what, "use the `layer` scheme")) << what;
  }
  try {
    cosim::PaperRunner runner(m);
    ADD_FAILURE() << "PaperRunner accepted a shell node rotating on both sides";
  } catch (const ModelError& e) {
    EXPECT_TRUE(has(e.what(), "carries rotations in domains")) << e.what();
  }
}
