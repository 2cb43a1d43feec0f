#include "apps/cmd_hic.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "apps/result_head.h"
#include "core/errors.h"
#include "solver/io/result_reader.h"
#include "solver/signal/cfc_filter.h"
#include "solver/signal/head_metrics.h"
#include "solver/signal/hic.h"
#include "solver/signal/sampling.h"
#include "solver/signal/signal_csv.h"

namespace crashlink::apps {

namespace {

/// HDF5 files start with this signature (at offset 0 when there is no user block, as ours).
bool looks_like_hdf5(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  in.read(head.data(), head.size());
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  if (in.gcount() == 8 && std::memcmp(head.data(), kSignature, 8) == 0) return true;
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".h5" || ext == ".hdf5";
}

/// A history to evaluate: channels[c] sampled at time_s; resultant = |channels| (one channel: the
/// value as given).
struct Channels {
  std::vector<double> time_s;
  std::vector<std::vector<double>> channels;
};

std::string ms(double t_s) {
  return fmt::format("{:.3f}", 1e3 * t_s);
}

}  // namespace

CLI::App* add_hic_command(CLI::App& app, HicOptions& options) {
  auto* cmd = app.add_subcommand(
      "hic", "HIC15 / HIC36 of a head acceleration: CSV (time_s,accel_g) or result.h5 --probe");
  cmd->add_option("file", options.file, "CSV file (header time_s,accel_g) or result.h5")
      ->required();
  cmd->add_option("--probe", options.probe, "probe name in result.h5 (/history/probes/NAME)");
  cmd->add_option("--cfc", options.cfc,
                  "SAE J211/1 channel filter before HIC: 1000 | 600 | 180 | 60 | none "
                  "(default: 1000 for result.h5, none for CSV)")
      ->check(CLI::IsMember({"1000", "600", "180", "60", "none"}));
  cmd->add_option("--window", options.window_ms, "15 | 36: print only HIC15 or HIC36")
      ->check(CLI::IsMember({15, 36}));
  cmd->add_option("--csv-out", options.csv_out,
                  "write the filtered resultant (time_ms,accel_g) to this CSV file");
  return cmd;
}

int run_hic(const HicOptions& options, std::FILE* out) {
  const std::string& file = options.file;
  if (!std::filesystem::is_regular_file(file)) {
    throw InputError(
        fmt::format("hic: {}: no such file; give a CSV (time_s,accel_g) or a "
                    "result.h5 with --probe NAME",
                    file));
  }
  const bool is_result = looks_like_hdf5(file);
  Channels h;
  std::string source = file;
  if (is_result) {
    io::ResultReader reader(file);
    if (options.probe.empty()) {
      const auto names = reader.probe_names();
      throw InputError(fmt::format(
          "hic: {} is a result file: name the head probe with --probe NAME; the file has {}", file,
          names.empty() ? std::string("no probes")
                        : fmt::format("probe(s): {}", fmt::join(names, ", "))));
    }
    io::ProbeHistory p = reader.probe(options.probe);
    source =
        fmt::format("{}, probe '{}'{}", file, p.name, p.kind.empty() ? "" : " (" + p.kind + ")");
    const std::size_t k = p.size();
    h.time_s = std::move(p.time_s);
    h.channels.assign(3, std::vector<double>(k));
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t c = 0; c < 3; ++c) h.channels[c][i] = p.acceleration_m_s2[3 * i + c];
    }
  } else {
    if (!options.probe.empty()) {
      throw InputError(fmt::format(
          "hic: --probe {} applies to result.h5 files; {} is read as a CSV (time_s,accel_g)",
          options.probe, file));
    }
    signal::CsvSignal s = signal::read_signal_csv(file);
    h.time_s = std::move(s.time_s);
    h.channels.push_back(std::move(s.accel_g));
  }
  const std::string cfc_text = options.cfc.empty() ? (is_result ? "1000" : "none") : options.cfc;
  if (cfc_text != "none" && !signal::is_cfc_class(std::atoi(cfc_text.c_str()))) {
    throw InputError(fmt::format("hic: --cfc {}: use 1000, 600, 180, 60 or none", cfc_text));
  }
  const int cfc = cfc_text == "none" ? 0 : std::atoi(cfc_text.c_str());
  const double to_g = is_result ? 1.0 / signal::kStandardGravity_m_s2 : 1.0;
  const signal::HeadMetrics m = signal::head_metrics(h.time_s, h.channels, to_g, cfc, source);
  std::fprintf(out, "crashlink hic: %s: %zu samples, %s - %s ms\n", source.c_str(), h.time_s.size(),
               ms(h.time_s.front()).c_str(), ms(h.time_s.back()).c_str());
  if (m.max_step_s - m.min_step_s <= signal::Sampling::kUniformTolerance * m.mean_step_s) {
    std::fprintf(out, "sampling: uniform, step %.6g us (%.6g kHz)\n", 1e6 * m.mean_step_s,
                 1e-3 / m.mean_step_s);
  } else if (m.resampled) {
    std::fprintf(out,
                 "sampling: non-uniform (steps %.6g - %.6g us); resampled linearly to a uniform "
                 "%.6g us (%zu samples) for the CFC filter\n",
                 1e6 * m.min_step_s, 1e6 * m.max_step_s, 1e6 * m.mean_step_s, m.time_s.size());
  } else {
    std::fprintf(out, "sampling: non-uniform (steps %.6g - %.6g us), used as is\n",
                 1e6 * m.min_step_s, 1e6 * m.max_step_s);
  }
  if (cfc != 0) {
    std::fprintf(out, "filter: CFC %d (SAE J211/1 4-pole phaseless Butterworth)\n", cfc);
  } else {
    std::fprintf(out, "filter: none\n");
  }
  std::fprintf(out, "%s = %.6g g at %s ms\n",
               is_result ? "peak resultant acceleration" : "peak acceleration", m.peak_g,
               ms(m.peak_time_s).c_str());
  for (const auto& [window_ms, r] : {std::pair{15, m.hic15}, std::pair{36, m.hic36}}) {
    if (options.window_ms != 0 && options.window_ms != window_ms) continue;
    std::fprintf(out, "HIC%d = %.1f (t1 = %s ms, t2 = %s ms)\n", window_ms, r.hic,
                 ms(r.t1_s).c_str(), ms(r.t2_s).c_str());
  }
  if (!options.csv_out.empty()) write_head_csv(options.csv_out, m, "hic: --csv-out");
  std::fflush(out);
  return 0;
}

}  // namespace crashlink::apps
