// bench_stable_step: how close each element-local stable-step estimate comes to the step a mesh
// allows (studies/stable_step_survey.h; docs/elements.md "Stable step survey"). For quads and
// hexes at aspect ratios 1 to 5 and distortions 0 to 0.4, free and clamped, it prints the patch's
// 2/omega_max and each estimate's ratio to it: the kernel's (what runs use), the element's own
// eigenvalue bound, LS-DYNA's default lengths; and a global estimate, the power method on the
// patch's M^-1 K after 10 and 30 iterations. A ratio above 1 is an unstable estimate.
//   bench_stable_step [--n N] [--kind quad|hex|both] [--vibrate CYCLES]
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "studies/stable_step_survey.h"

namespace {

int usage(const char* what) {
  std::fprintf(stderr,
               "bench_stable_step: %s\nusage: bench_stable_step [--n N] [--kind quad|hex|both] "
               "[--vibrate CYCLES]\n",
               what);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace crashlink::studies;
  int n = 5;
  std::string kind = "both";
  long long vibrate = 0;  // > 0: also a free vibration of this many cycles at dt_scale 1.0
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--n" && i + 1 < argc) {
      n = std::atoi(argv[++i]);
      if (n < 1 || n > 12) return usage("--n must be in [1, 12]");
    } else if (a == "--vibrate" && i + 1 < argc) {
      vibrate = std::atoll(argv[++i]);
      if (vibrate < 2) return usage("--vibrate takes a cycle count >= 2");
    } else if (a == "--kind" && i + 1 < argc) {
      kind = argv[++i];
      if (kind != "quad" && kind != "hex" && kind != "both")
        return usage("--kind: quad, hex or both");
    } else {
      return usage(("unknown argument " + a).c_str());
    }
  }
  std::vector<PatchKind> kinds;
  if (kind != "hex") kinds.push_back(PatchKind::Quad);
  if (kind != "quad") kinds.push_back(PatchKind::Hex);
  std::printf("%-42s %9s %11s %7s %7s %7s %7s %7s %7s\n", "patch", "elements", "2/w_max s",
              "kernel", "element", "lsdyna", "pow10", "pow30", "global");
  struct Range {
    double lo = 1e300, hi = 0.0;
    void add(double r) {
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
  };
  std::map<std::string, Range> ranges;
  for (const auto k : kinds)
    for (const double aspect : {1.0, 2.0, 3.0, 5.0})
      for (const double distort : {0.0, 0.2, 0.4})
        for (const bool clamped : {false, true}) {
          const PatchShape s{
              .kind = k, .n = n, .aspect = aspect, .distort = distort, .clamped = clamped};
          const auto r = survey_patch(s);
          const double kr = r.dt_kernel_s / r.dt_patch_s, er = r.dt_element_s / r.dt_patch_s,
                       lr = r.dt_lsdyna_s / r.dt_patch_s;
          const double gr = r.dt_global_s / r.dt_patch_s;
          if (vibrate > 0) {
            const auto v = vibrate_patch(s, vibrate);
            std::printf(
                "%-42s vibration: %lld cycles of %.4e s, E_max/E_1 %.4f, E_end/E_1 %.4f%s\n",
                describe(s).c_str(), static_cast<long long>(v.cycles), v.dt_first_s,
                v.e_max_J / v.e0_J, v.e_end_J / v.e0_J,
                v.error.empty() ? "" : (" STOPPED: " + v.error).c_str());
            ranges[(k == PatchKind::Quad ? "quad" : "hex") + std::string(" E_max/E_1")].add(
                v.e_max_J / v.e0_J);
          }
          std::printf("%-42s %9d %11.4e %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f\n", describe(s).c_str(),
                      r.elements, r.dt_patch_s, kr, er, lr, r.power_ratio[1], r.power_ratio[2], gr);
          std::fflush(stdout);
          const std::string name = k == PatchKind::Quad ? "quad" : "hex";
          ranges[name + " kernel"].add(kr);
          ranges[name + " element"].add(er);
          ranges[name + " lsdyna"].add(lr);
          ranges[name + " power 10"].add(r.power_ratio[1]);
          ranges[name + " power 30"].add(r.power_ratio[2]);
          ranges[name + " power 100"].add(r.power_ratio[3]);
          ranges[name + " global"].add(gr);
        }
  std::printf("\nratio to the patch's 2/omega_max (1: the largest stable step; > 1: unstable)\n");
  for (const auto& [name, r] : ranges)
    std::printf("  %-16s %.3f .. %.3f\n", name.c_str(), r.lo, r.hi);
  return 0;
}
