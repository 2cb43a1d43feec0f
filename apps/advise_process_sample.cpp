#include "apps/advise_process_sample.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "apps/cmd_run.h"
#include "apps/scenario_variant.h"
#include "apps/timing_reader.h"
#include "core/errors.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::apps {

namespace {

namespace fs = std::filesystem;

struct Cost {
  double total_s = 0.0;
  double coordinator_s = 0.0;
};

Cost run_sample(const std::string& scenario, const std::string& mode, double step_safety,
                const fs::path& out) {
  RunCommandOptions r;
  r.scenario = scenario;
  r.out = out.string();
  r.mode = mode;
  r.quiet = true;
  r.step_safety = step_safety;
  int rc = 0;
  try {
    rc = run_run(r);
  } catch (const Error& e) {
    throw InputError(fmt::format("advise --process-sample: the {} sample run into {} failed: {}",
                                 mode, out.string(), e.what()));
  }
  const auto t = read_timing((out / "result.h5").string());
  if (rc != 0 || !t) {
    throw InputError(
        fmt::format("advise --process-sample: the {} sample run into {} failed (exit "
                    "code {}); run it with `crashlink run {} --mode {}` to see why",
                    mode, out.string(), rc, scenario, mode));
  }
  return {t->total_cpu_seconds(), t->coordinator_cpu_seconds};
}

}  // namespace

ProcessSample sample_on_processes(const std::string& scenario, double fraction,
                                  double step_safety) {
  if (!(fraction > 0.0 && fraction <= 0.5)) {
    throw InputError(
        fmt::format("advise --process-sample {}: the fraction of the end time must be "
                    "in (0, 0.5] (the sample runs to F and to 2F)",
                    fraction));
  }
  const auto model = io::read_scenario(scenario);
  if (model.domains.size() < 2) {
    throw InputError(
        fmt::format("advise --process-sample: {} has no `domains:` to run in multi; "
                    "paste the advised block first",
                    scenario));
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("crashlink-advise-{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  struct Cleanup {
    fs::path d;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
  } cleanup{dir};
  Cost cost[2][2];  // [mode: mono, multi][length: F, 2F]
  for (int len = 0; len < 2; ++len) {
    const double end_s = model.controls.end_time_s * fraction * (len + 1);
    const std::string variant = (dir / fmt::format("sample{}.yaml", len)).string();
    write_scenario_variant(scenario, {"controls", "end_time"}, fmt::format("{:.17g}", end_s),
                           variant);
    for (int m = 0; m < 2; ++m) {
      const char* mode = m == 0 ? "mono" : "multi";
      std::fprintf(stderr, "advise: process sample, %s to %.4g s\n", mode, end_s);
      cost[m][len] = run_sample(variant, mode, step_safety, dir / fmt::format("{}{}", mode, len));
    }
  }
  ProcessSample s;
  s.fraction = fraction;
  s.mono_cpu_s = cost[0][1].total_s - cost[0][0].total_s;
  s.multi_cpu_s = cost[1][1].total_s - cost[1][0].total_s;
  if (!(s.mono_cpu_s > 0.0 && s.multi_cpu_s > 0.0)) {
    throw InputError(fmt::format(
        "advise --process-sample {}: the CPU times did not grow from F to 2F (mono {:.3f} -> "
        "{:.3f} s, multi {:.3f} -> {:.3f} s): the sample is too short to time; use a larger F",
        fraction, cost[0][0].total_s, cost[0][1].total_s, cost[1][0].total_s, cost[1][1].total_s));
  }
  s.gain = s.mono_cpu_s / s.multi_cpu_s;
  s.coordinator_share = (cost[1][1].coordinator_s - cost[1][0].coordinator_s) / s.multi_cpu_s;
  return s;
}

}  // namespace crashlink::apps
