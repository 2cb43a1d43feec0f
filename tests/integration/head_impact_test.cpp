// The head-impact scene (issue #5), CI variant scenarios/head_impact_small.yaml, end to end over
// real processes: `crashlink run --mode multi --reference mono` runs the coupled scene, then the
// mono reference, then prints the paper's Table 1 (`crashlink compare`). Checked: both runs
// finish, the five interfaces exist (three links, two cross-domain contacts: the decomposition
// moves the contact surfaces into the wiper domain), the wiper is hit (the hood-wiper contact
// carries force), and the multi HIC15 and peak acceleration agree with mono.
//
// Tolerances: the small variant's 20 mm hood shells and 8 mm wiper hexes make a coarse, chattering
// penalty contact whose details depend on the step (the wiper's fixed step is 14 % below mono's):
// measured +0.05 % on HIC15, +8 % on the sampled peak, -12 % on the hood-wiper impulse (the full
// scene: HIC15 -0.49 %, impulse -0.07 %). Bounds: HIC15 3 %, impulse 20 %; a broken coupling
// (the contact lost across the domains, a link not transmitted) changes HIC by tens of per cent
// (without the wiper hit the peak is ~220 g instead of ~500 g) and the impulse entirely.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "solver/io/result_reader.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace {

using crashlink::testing::run_command;

/// The number after `key` in `text` (the first occurrence after `from`), NaN if absent.
double number_after(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto at = text.find(key, from);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + key.size(), nullptr);
}

}  // namespace

TEST(HeadImpact, SmallSceneMultiMatchesMonoAndPrintsTable1) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_head_impact_small_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink run " +
                          CRASHLINK_SOURCE_DIR +
                          "/scenarios/head_impact_small.yaml --mode multi --reference mono "
                          "--quiet --out " +
                          dir.string();
  int status = -1;
  const std::string out = run_command(cmd, status);
  ASSERT_EQ(status, 0) << out;
  std::printf("%s\n", out.substr(out.find("crashlink compare")).c_str());

  // Table 1 and its figures.
  const auto table = out.find("crashlink compare");
  ASSERT_NE(table, std::string::npos) << out;
  const double gain = number_after(out, "gain ", out.find("CPU: reference", table));
  const double ideal = number_after(out, "ideal gain from element counts and steps ", table);
  EXPECT_TRUE(std::isfinite(gain) && gain > 0.0) << out;
  EXPECT_TRUE(std::isfinite(ideal) && ideal > 1.0) << out;
  const double hic_mono = number_after(out, "HIC15 ", table);
  const double hic_multi = number_after(out, " vs ", out.find("HIC15 ", table));
  ASSERT_TRUE(std::isfinite(hic_mono) && std::isfinite(hic_multi)) << out;
  std::printf("[measured] head_impact_small HIC15 mono %.1f multi %.1f (%+.2f %%)\n", hic_mono,
              hic_multi, 100.0 * (hic_multi - hic_mono) / hic_mono);
  EXPECT_GT(hic_mono, 500.0);  // the wiper hit makes it a hard impact
  EXPECT_NEAR(hic_multi, hic_mono, 0.03 * hic_mono);

  // Several pairs: one line each and the medians. (mono, multi) and (mono, mono): gains g and 1,
  // median (g + 1) / 2 (the mean of the middle two); an odd count of files is refused, and so is
  // a swapped pair (multi, mono), whose "gain" 1/g read as a share of the ideal (issue 20).
  {
    const std::string crashlink = std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink compare ";
    const std::string mono_h5 = (dir / "reference" / "result.h5").string();
    const std::string multi_h5 = (dir / "result.h5").string();
    int st = -1;
    const std::string two =
        run_command(crashlink + mono_h5 + " " + multi_h5 + " " + mono_h5 + " " + mono_h5, st);
    ASSERT_EQ(st, 0) << two;
    const auto at = two.find("\nmedian ");
    ASSERT_NE(at, std::string::npos) << two;
    std::istringstream row(two.substr(at + 8));
    double ref_cpu = 0.0, run_cpu = 0.0, median_gain = 0.0;
    row >> ref_cpu >> run_cpu >> median_gain;
    EXPECT_NEAR(median_gain, 0.5 * (gain + 1.0), 2e-3) << two;
    const std::string swapped = run_command(crashlink + multi_h5 + " " + mono_h5, st);
    EXPECT_EQ(WEXITSTATUS(st), 2) << swapped;
    EXPECT_NE(swapped.find("swap them"), std::string::npos) << swapped;
    const std::string odd = run_command(crashlink + mono_h5 + " " + multi_h5 + " " + mono_h5, st);
    EXPECT_NE(st, 0) << odd;
    EXPECT_NE(odd.find("in pairs"), std::string::npos) << odd;
  }

  // The coupled result: interfaces and contacts.
  crashlink::io::ResultReader multi((dir / "result.h5").string());
  crashlink::io::ResultReader mono((dir / "reference" / "result.h5").string());
  const auto hood_wiper = multi.contact("hood_wiper");
  const auto hood_wiper_mono = mono.contact("hood_wiper");
  auto impulse = [](const crashlink::io::ContactHistory& c) {  // N s, trapezoids
    double sum = 0.0;
    auto f = [&](std::size_t i) {
      return std::hypot(c.force_N[3 * i], c.force_N[3 * i + 1], c.force_N[3 * i + 2]);
    };
    for (std::size_t i = 1; i < c.time_s.size(); ++i)
      sum += 0.5 * (f(i) + f(i - 1)) * (c.time_s[i] - c.time_s[i - 1]);
    return sum;
  };
  std::printf("[measured] hood-wiper contact impulse mono %.3f N s, multi %.3f N s\n",
              impulse(hood_wiper_mono), impulse(hood_wiper));
  EXPECT_GT(impulse(hood_wiper_mono), 1.0) << "the hood must hit the wiper";
  EXPECT_NEAR(impulse(hood_wiper), impulse(hood_wiper_mono), 0.2 * impulse(hood_wiper_mono));

  // Contact energy per interface (issue 21): in both files at their contacts' sample times, and
  // in both summaries (multi, then mono) with every interface.
  for (const auto* file : {&multi, &mono}) {
    for (const auto& name : file->contact_names()) {
      const auto c = file->contact(name);
      EXPECT_EQ(c.energy_J.size(), c.time_s.size()) << name;
      EXPECT_GT(c.energy_J.size(), 0u) << name;
    }
  }
  std::printf("[measured] hood_wiper contact energy at the end: mono %.4g J, multi %.4g J\n",
              hood_wiper_mono.energy_J.back(), hood_wiper.energy_J.back());
  std::size_t summaries = 0;
  for (auto at = out.find("contact energy [J] at the end:"); at != std::string::npos;
       at = out.find("contact energy [J] at the end:", at + 1)) {
    const std::string line = out.substr(at, out.find('\n', at) - at);
    EXPECT_NE(line.find("'hood_wiper'"), std::string::npos) << line;
    ++summaries;
  }
  EXPECT_EQ(summaries, 2u) << out;

  // The report of the multi run (README): every PNG written and non-empty.
  const std::string report =
      std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink report " + (dir / "result.h5").string();
  const std::string report_out = run_command(report, status);
  ASSERT_EQ(status, 0) << report_out;
  for (const char* png : {"head_acceleration.png", "energy.png", "interface_drift.png",
                          "contact_forces.png", "head_cfc1000.csv", "contact_forces_cfc180.csv"}) {
    const auto path = dir / "report" / png;
    ASSERT_TRUE(std::filesystem::exists(path)) << path << "\n" << report_out;
    EXPECT_GT(std::filesystem::file_size(path), 1000u) << path;
  }
  // The contact forces are plotted after CFC 180 (the CSV the plot reads says so per row).
  std::ifstream csv(dir / "report" / "contact_forces_cfc180.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header, "contact,filter,time_ms,force_kN");
  std::map<std::string, std::size_t> filtered;  // contact -> rows filtered by CFC 180
  while (std::getline(csv, row))
    if (row.find(",CFC 180,") != std::string::npos) ++filtered[row.substr(0, row.find(','))];
  EXPECT_GT(filtered["hood_wiper"], 100u);
}

// `crashlink sweep` on the CI variant (README): every configuration runs, the CSV has a finite
// row per configuration, the chart is written. Conventional mass scaling of the wiper up to the
// body's step must cost less CPU than mono and change the head's answer (the wiper gets heavier:
// measured +60 % on HIC15): the trade-off the chart shows. A refinement of the wiper bar
// (--refine wiper_bar=100: 4 mm long hexes) raises the step ratio and runs its own mono and multi.
TEST(HeadImpact, SweepOfTheSmallSceneWritesTheChart) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink_sweep_small_" + std::to_string(::getpid()));
  const crashlink::proc_test::RemoveIfPassed cleanup{dir};
  std::filesystem::remove_all(dir);
  int status = -1;
  const std::string out = run_command(
      std::string(CRASHLINK_BINARY_DIR) + "/apps/crashlink sweep " + CRASHLINK_SOURCE_DIR +
          "/scenarios/head_impact_small.yaml --refine wiper_bar=100 --out " + dir.string(),
      status);
  ASSERT_EQ(status, 0) << out;
  ASSERT_GT(std::filesystem::file_size(dir / "sweep.png"), 1000u);
  std::ifstream f(dir / "sweep.csv");
  std::string line;
  std::getline(f, line);
  std::map<std::string, std::vector<double>> row;
  std::map<std::string, std::string> text;
  while (std::getline(f, line)) {
    std::stringstream ss(line);
    std::string name, cell;
    std::getline(ss, name, ',');
    text[name] = line;
    if (line.find(",,") != std::string::npos) continue;  // stopped: no figures, a note
    for (int k = 0; k < 11 && std::getline(ss, cell, ','); ++k)
      row[name].push_back(std::stod(cell));
  }
  // The paper scheme at multi's ratio (3 on this scene): stopped by its own guard, with the time
  // and the guard's message in the row (measured: at 3.78 ms of 12), or run to the end. No
  // contact creates energy on this scene any more (issue 21): a stop must be the scheme's.
  for (const char* name : {"paper", "paper_no_drift"}) {
    ASSERT_EQ(text.count(name), 1u) << out;
    if (row.count(name) == 0) {
      EXPECT_NE(text[name].find("went unstable"), std::string::npos) << text[name];
      EXPECT_EQ(text[name].find("created by contacts"), std::string::npos) << text[name];
      EXPECT_NE(text[name].find("H/h = 3"), std::string::npos) << text[name];
    }
    row.erase(name);
  }
  // Conventional mass scaling of the wiper runs to the end: cheaper and wrong (below; measured
  // CPU 0.39 of mono, HIC15 +95 %). Before issue 21's contact it was stopped by the guard
  // ('headform_hood' created 24.2 J, 11.4 % of E0, at 4.1 ms).
  ASSERT_EQ(row.size(), 7u) << out;
  for (const auto& [name, v] : row) {
    ASSERT_EQ(v.size(), 11u) << name;
    for (double x : v) EXPECT_TRUE(std::isfinite(x)) << name;
  }
  EXPECT_EQ(row["mono"][1], 1.0);                    // cpu_over_mono
  EXPECT_LT(row["mass_scaled"][1], 1.0);             // cheaper ...
  EXPECT_GT(std::abs(row["mass_scaled"][4]), 10.0);  // ... and wrong: HIC15 error %
  EXPECT_GT(row["mass_scaled"][9], 0.0);             // added mass, kg
  EXPECT_LT(std::abs(row["multi"][4]), 3.0);         // HIC15 error %, as the test above
  EXPECT_LT(std::abs(row["lts"][4]), 5.0);  // lts (issue 25): measured +2.9 % (layer +1.8 %)
  // the refined scene: its own mono is its reference, its step ratio is larger (measured 4.30
  // against 2.71), multi's HIC15 still within 3 % of that mono (measured -0.80 %)
  EXPECT_EQ(row["mono_wiper_bar100"][1], 1.0);
  EXPECT_GT(row["multi_wiper_bar100"][10], 1.4 * row["multi"][10]);
  EXPECT_LT(std::abs(row["multi_wiper_bar100"][4]), 3.0);
}
