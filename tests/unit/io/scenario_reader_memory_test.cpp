// The reader's peak memory on a long list stays a small multiple of the input (issue 20, item
// 13; docs/benchmarks.md "Scenario reader"). Memory, unlike time, is deterministic: the peak
// resident memory (VmHWM, reset to the current VmRSS through /proc/self/clear_refs) is measured
// around parse_scenario of a generated scenario with 2 M node ids in one flow list. Nothing
// here is timed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "solver/io/scenario_reader.h"
#include "solver/model/model.h"

namespace crashlink::io {
namespace {

long status_kib(const std::string& field) {  // "VmHWM:   1234 kB" in /proc/self/status
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field + ":", 0) == 0) return std::atol(line.c_str() + field.size() + 1);
  return -1;
}

bool reset_peak() {  // Linux >= 4.0: "5" sets VmHWM to the current VmRSS
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

/// A 10x10x10 box (1331 nodes) whose node set `listed` has `n` ids, 16 a line, fixed in z.
std::string scenario_with_ids(std::size_t n) {
  std::string s =
      "name: big\ncontrols: {end_time: 1.0e-4}\nmaterials:\n"
      "  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}\n"
      "parts:\n  block:\n    material: steel\n"
      "    mesh: {generator: box, size: [0.1, 0.1, 0.1], divisions: [10, 10, 10]}\n"
      "node_sets:\n  listed:\n    nodes: [";
  s.reserve(s.size() + 6 * n + 64);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) s += k % 16 == 0 ? ",\n      " : ", ";
    s += std::to_string((k * 7919) % 1331 + 1);
  }
  return s + "]\nboundary:\n  - {nodes: listed, fix: [z]}\n";
}

TEST(ScenarioReaderMemory, PeakIsASmallMultipleOfTheInput) {
  const std::size_t ids = 2'000'000;
  const std::string text = scenario_with_ids(ids);  // ~11.5 MB, held by the caller
  if (!reset_peak()) GTEST_SKIP() << "/proc/self/clear_refs not writable: cannot reset VmHWM";
  const long before_kib = status_kib("VmRSS");
  const auto model = parse_scenario(text, "big.yaml");
  const long peak_kib = status_kib("VmHWM");
  ASSERT_GT(before_kib, 0);
  ASSERT_GT(peak_kib, 0);

  // The reader made the model: every node is in the list, fixed in z only.
  ASSERT_EQ(model.fixed.size(), 1331u);
  for (const auto f : model.fixed) EXPECT_EQ(f, model::kUz);

  // Bound: the parsed tree keeps each list item's text (under the input's size) and a 4-byte
  // offset, the selection reader a 4-byte node index per id: with ~5.8 input bytes per id,
  // about 2.2 times the input, plus a few MiB of model and allocator. 4x leaves room for
  // allocator rounding; the yaml-cpp node tree measured 60x and more (docs/benchmarks.md).
  const double input_mib = static_cast<double>(text.size()) / (1024.0 * 1024.0);
  const double growth_mib = static_cast<double>(peak_kib - before_kib) / 1024.0;
  RecordProperty("input_mib", std::to_string(input_mib));
  RecordProperty("growth_mib", std::to_string(growth_mib));
  EXPECT_LE(growth_mib, 4.0 * input_mib)
      << "peak memory grew " << growth_mib << " MiB reading a " << input_mib << " MiB scenario";
}

}  // namespace
}  // namespace crashlink::io
