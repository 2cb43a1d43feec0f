// lts with variable steps over processes: the first owner step is planned from what the leader's
// cost rule sees at t = 0 (coupling::lts_variable_first_proposals; docs/multirate.md "The first
// owner step's kind"), so the fine side's substep count does not change after it. The scene: a
// steel bar, fine [0, 0.08] m in 8 hexes of 10 mm and coarse [0.08, 0.6] m in 21 of 24.8 mm, the
// x = 0 nodes started at 30 m/s (bar_parts_yaml's load and fixed end). The plan's ceil rule took
// 3 substeps, the rule 2: the fine step rose 38 % after the first owner step and the energy
// balance fell to -4.39 % before the wave reached the interface (fixed lts -0.02 %, `layer` with
// variable steps -0.42 %, mono -0.23 %); planned from the rule's inputs it is -0.53 %. Both orders
// of the domains in the scenario.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "solver/io/result_reader.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;

/// Every instant [s] domain `name` wrote a history row at (a row every cycle: the default).
std::vector<double> instants(const fs::path& out, const std::string& name) {
  std::vector<double> t;
  for (const auto& r :
       crashlink::io::ResultReader((out / "domains" / (name + ".h5")).string()).glstat())
    t.push_back(r.time_s);
  return t;
}

/// The fine instants in each owner step (coarse[k], coarse[k + 1]].
std::vector<int> substeps(const std::vector<double>& coarse, const std::vector<double>& fine) {
  std::vector<int> p;
  for (std::size_t k = 0; k + 1 < coarse.size(); ++k) {
    const double tol = 1e-3 * (coarse[k + 1] - coarse[k]);
    int n = 0;
    for (const double t : fine)
      if (t > coarse[k] + tol && t <= coarse[k + 1] + tol) ++n;
    p.push_back(n);
  }
  return p;
}

/// The run summary's "energy balance error X %" [%].
double balance_percent(const std::string& out) {
  const std::string key = "energy balance error ";
  const auto at = out.rfind(key);
  if (at == std::string::npos) return NAN;
  return std::strtod(out.c_str() + at + key.size(), nullptr);
}

}  // namespace

TEST(LtsFirstOwnerStep, TheSubstepCountHoldsFromTheFirstOwnerStepInEitherDomainOrder) {
  std::string yaml = crashlink::proc_test::bar_parts_yaml(
      "bar_kick", 2.0e-4, {{"fine", 0.0, 0.08, 8}, {"coarse", 0.08, 0.52, 21}},
      "initial_velocity:\n  - nodes: {box: {min: [-1.0, -1.0, -1.0], max: [1.0e-4, 1.0, 1.0]}}\n"
      "    velocity: [30.0, 0.0, 0.0]\n");
  const std::string order = "domains:\n  fine: {parts: [fine]}\n  coarse: {parts: [coarse]}\n";
  ASSERT_NE(yaml.find(order), std::string::npos);
  for (const bool coarse_first : {false, true}) {
    if (coarse_first)
      yaml.replace(yaml.find(order), order.size(),
                   "domains:\n  coarse: {parts: [coarse]}\n  fine: {parts: [fine]}\n");
    const fs::path dir =
        crashlink::proc_test::fresh_dir(coarse_first ? "lts_first_cf" : "lts_first_ff");
    const std::string scenario = crashlink::proc_test::write_file(dir / "scene.yaml", yaml);
    int status = -1;
    const std::string out = crashlink::testing::run_command(
        crashlink::proc_test::bin("crashlink") + " run " + scenario +
            " --mode multi --coupling lts --variable-steps --quiet --out " + (dir / "out").string(),
        status);
    ASSERT_EQ(status, 0) << out;
    const auto p = substeps(instants(dir / "out", "coarse"), instants(dir / "out", "fine"));
    ASSERT_GT(p.size(), 20u) << out;
    std::string seq;
    for (const int n : p) seq += std::to_string(n) + " ";
    EXPECT_EQ(p[0], p[1]) << "the fine step jumps after the first owner step: " << seq;
    // the balance: -4.39 % with the jump; -0.53 % without it, between mono's -0.23 % and `layer`
    // variable's -0.42 % and twice them
    const double balance = balance_percent(out);
    std::printf(
        "[measured] lts variable, 30 m/s bar, %s first: p per owner step %s; balance %.4f %%\n",
        coarse_first ? "coarse" : "fine", seq.substr(0, 40).c_str(), balance);
    EXPECT_LT(std::abs(balance), 1.0) << out;
    std::error_code ec;
    if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
  }
}
