#include "apps/cmd_compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "apps/result_head.h"
#include "apps/timing_reader.h"
#include "core/errors.h"
#include "core/median.h"
#include "solver/io/result_reader.h"

namespace crashlink::apps {

namespace {

TimingRecord timing_of(const std::string& path) {
  auto t = read_timing(path);
  if (!t || t->domains.empty()) {
    throw InputError(fmt::format(
        "compare: {} has no /timing: not the result.h5 of a finished run (rerun it, or gather a "
        "coupled run's files with `crashlink gather`)",
        path));
  }
  return *t;
}

double element_cycles_per_second(const TimingRecord& t) {
  double sum = 0.0;
  for (const auto& d : t.domains) {
    if (d.dt_min_s > 0.0) sum += static_cast<double>(d.elements) / d.dt_min_s;
  }
  return sum;
}

std::int64_t elements_of(const TimingRecord& t) {
  std::int64_t sum = 0;
  for (const auto& d : t.domains) sum += d.elements;
  return sum;
}

/// The two files are runs of one model (the same node ids and parts with the same elements) and
/// in the order reference, run (a mono reference is never the second file); InputError otherwise.
void check_pair(const std::string& ref_path, const TimingRecord& ref, const std::string& run_path,
                const TimingRecord& run) {
  if (ref.domains.size() > 1 && run.domains.size() == 1)
    throw InputError(fmt::format(
        "compare: the first file is the reference and the second the run to compare; {} is a "
        "coupled run ({} domains) and {} a single-domain one: swap them",
        ref_path, ref.domains.size(), run_path));
  const io::ResultReader a(ref_path), b(run_path);
  const auto na = a.node_ids(), nb = b.node_ids();
  const auto pa = a.mesh_parts(), pb = b.mesh_parts();
  bool same = na == nb && pa.size() == pb.size();
  for (std::size_t i = 0; same && i < pa.size(); ++i)
    same = pa[i].name == pb[i].name && pa[i].element_ids == pb[i].element_ids;
  if (!same)
    throw InputError(fmt::format(
        "compare: {} ({} nodes, {} parts) and {} ({} nodes, {} parts) are not runs of the same "
        "model (node ids or parts' elements differ); compare runs of one scenario",
        ref_path, na.size(), pa.size(), run_path, nb.size(), pb.size()));
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareOptions& options) {
  auto* cmd = app.add_subcommand(
      "compare",
      "the paper's Table 1 for two runs of a scene (or several pairs, with their medians): CPU, "
      "gain, HIC difference");
  cmd->add_option("files", options.files,
                  "result.h5 of the reference (mono) run, then of the run to compare (split / "
                  "multi); more such pairs (repeated runs) add a line each and their medians")
      ->required()
      ->expected(2, 1 << 20)
      ->check(CLI::ExistingFile);
  cmd->add_option("--probe", options.probe,
                  "head probe (default: the reference's first rigid-body probe)");
  return cmd;
}

Comparison compare_runs(const CompareOptions& options, std::FILE* out) {
  const TimingRecord ref = timing_of(options.reference);
  const TimingRecord run = timing_of(options.run);
  check_pair(options.reference, ref, options.run, run);
  Comparison c;
  c.cpu_reference_s = ref.total_cpu_seconds();
  c.cpu_run_s = run.total_cpu_seconds();
  c.coordinator_cpu_s = run.coordinator_cpu_seconds;
  c.wall_reference_s = ref.wall_seconds;
  c.wall_run_s = run.wall_seconds;
  c.gain = c.cpu_run_s > 0.0 ? c.cpu_reference_s / c.cpu_run_s : 0.0;
  const double ec_run = element_cycles_per_second(run);
  c.ideal_gain = ec_run > 0.0 ? element_cycles_per_second(ref) / ec_run : 0.0;
  c.wall_gain = c.wall_run_s > 0.0 ? c.wall_reference_s / c.wall_run_s : 0.0;
  c.coordinator_share = c.cpu_run_s > 0.0 ? c.coordinator_cpu_s / c.cpu_run_s : 0.0;

  // Columns: the reference's domains, the run's domains, coordinator, total.
  std::vector<std::string> head{"", "reference"};
  std::vector<std::string> elements{"elements", ""}, step{"critical step [s]", ""},
      cycles{"cycles", ""}, cpu{"CPU [s]", ""}, threads{"threads", ""};
  auto add = [&](const io::DomainTiming& d, bool first_of_ref) {
    if (!first_of_ref) head.push_back(d.name);
    const std::size_t i = first_of_ref ? 1 : head.size() - 1;
    for (auto* row : {&elements, &step, &cycles, &cpu, &threads}) row->resize(head.size());
    threads[i] = fmt::format("{}", d.threads);
    elements[i] = fmt::format("{}", d.elements);
    step[i] = fmt::format("{:.4g}", d.dt_min_s);
    cycles[i] = fmt::format("{}", d.cycles);
    cpu[i] = fmt::format("{:.2f}", d.cpu_seconds);
  };
  if (ref.domains.size() == 1) {
    add(ref.domains.front(), true);
  } else {  // a coupled reference: one column per domain
    head.pop_back();
    for (const auto& d : ref.domains) add(d, false);
  }
  const std::size_t first_run_column = head.size();
  for (const auto& d : run.domains) add(d, false);
  head.push_back("coordinator");
  for (auto* row : {&elements, &step, &cycles, &cpu, &threads}) row->resize(head.size(), "-");
  cpu.back() = fmt::format("{:.2f}", run.coordinator_cpu_seconds);
  head.push_back("total");
  elements.push_back(fmt::format("{}", elements_of(run)));
  step.push_back("-");
  cycles.push_back("-");
  cpu.push_back(fmt::format("{:.2f}", c.cpu_run_s));
  std::int64_t run_threads = 0, ref_threads = 0;
  for (const auto& d : run.domains) run_threads += d.threads;
  for (const auto& d : ref.domains) ref_threads += d.threads;
  threads.push_back(fmt::format("{}", run_threads));
  // the threads row only when some solver ran on more than one (the paper's table has none)
  std::vector<const std::vector<std::string>*> rows{&head, &elements, &step, &cycles, &cpu};
  if (run_threads > static_cast<std::int64_t>(run.domains.size()) ||
      ref_threads > static_cast<std::int64_t>(ref.domains.size()))
    rows.push_back(&threads);

  std::fprintf(out, "crashlink compare: reference %s\n                   run       %s\n\n",
               options.reference.c_str(), options.run.c_str());
  std::vector<std::size_t> width(head.size(), 0);
  for (const auto* row : rows)
    for (std::size_t i = 0; i < row->size(); ++i) width[i] = std::max(width[i], (*row)[i].size());
  for (const auto* row : rows) {
    std::string line;
    for (std::size_t i = 0; i < row->size(); ++i) {
      if (i == first_run_column) line.append(" |");
      line.append(i == 0 ? fmt::format("{:<{}}", (*row)[i], width[i])
                         : fmt::format("  {:>{}}", (*row)[i], width[i]));
    }
    std::fprintf(out, "%s\n", line.c_str());
  }
  std::fprintf(out,
               "\nCPU: reference %.2f s, run %.2f s (coordinator %.2f s = %.2f %% of it)\n"
               "gain %.3f, ideal gain from element counts and steps %.3f: %.1f %% of ideal\n"
               "wall: reference %.2f s, run %.2f s: wall-clock gain %.3f\n",
               c.cpu_reference_s, c.cpu_run_s, c.coordinator_cpu_s, 100.0 * c.coordinator_share,
               c.gain, c.ideal_gain, c.ideal_gain > 0.0 ? 100.0 * c.gain / c.ideal_gain : 0.0,
               c.wall_reference_s, c.wall_run_s, c.wall_gain);
  // The fair clock (issue 24): mono on as many threads as the coupled run's solvers in all.
  std::fprintf(
      out, "cores: reference %lld thread%s, run %lld solver thread%s%s\n",
      static_cast<long long>(ref_threads), ref_threads == 1 ? "" : "s",
      static_cast<long long>(run_threads), run_threads == 1 ? "" : "s",
      ref_threads == run_threads
          ? ": the wall-clock gain is on equal cores"
          : fmt::format(" (for the gain on equal cores: --reference-threads {})", run_threads)
                .c_str());

  const io::ResultReader ref_reader(options.reference), run_reader(options.run);
  const std::string probe =
      options.probe.empty() ? first_rigid_body_probe(ref_reader) : options.probe;
  if (probe.empty()) {
    std::fprintf(out,
                 "head metrics: the reference has no rigid-body probe (name one with --probe)\n");
  } else {
    const signal::HeadMetrics a = result_head_metrics(ref_reader, options.reference, probe);
    const signal::HeadMetrics b = result_head_metrics(run_reader, options.run, probe);
    c.has_head = true;
    c.hic15_reference = a.hic15.hic;
    c.hic15_run = b.hic15.hic;
    c.hic15_difference = a.hic15.hic > 0.0 ? (b.hic15.hic - a.hic15.hic) / a.hic15.hic : 0.0;
    c.peak_g_reference = a.peak_g;
    c.peak_g_run = b.peak_g;
    auto rel = [](double x, double ref_value) {
      return ref_value != 0.0 ? 100.0 * (x - ref_value) / ref_value : 0.0;
    };
    std::fprintf(out,
                 "head '%s' (CFC 1000): HIC15 %.1f vs %.1f (%+.2f %%), HIC36 %.1f vs %.1f "
                 "(%+.2f %%), peak %.1f g vs %.1f g (%+.2f %%)\n",
                 probe.c_str(), a.hic15.hic, b.hic15.hic, 100.0 * c.hic15_difference, a.hic36.hic,
                 b.hic36.hic, rel(b.hic36.hic, a.hic36.hic), a.peak_g, b.peak_g,
                 rel(b.peak_g, a.peak_g));
  }
  std::fflush(out);
  return c;
}

using core::median;

Comparison print_medians(const std::vector<Comparison>& pairs, std::FILE* out) {
  auto med = [&](double Comparison::*field) {
    std::vector<double> x;
    for (const auto& c : pairs) x.push_back(c.*field);
    return median(x);
  };
  std::vector<double> of_ideal;
  for (const auto& c : pairs) of_ideal.push_back(c.ideal_gain > 0.0 ? c.gain / c.ideal_gain : 0.0);
  Comparison m;
  m.cpu_reference_s = med(&Comparison::cpu_reference_s);
  m.cpu_run_s = med(&Comparison::cpu_run_s);
  m.coordinator_cpu_s = med(&Comparison::coordinator_cpu_s);
  m.wall_reference_s = med(&Comparison::wall_reference_s);
  m.wall_run_s = med(&Comparison::wall_run_s);
  m.gain = med(&Comparison::gain);
  m.ideal_gain = med(&Comparison::ideal_gain);
  m.wall_gain = med(&Comparison::wall_gain);
  m.coordinator_share = med(&Comparison::coordinator_share);
  m.has_head = std::all_of(pairs.begin(), pairs.end(), [](const auto& c) { return c.has_head; });
  m.hic15_difference = med(&Comparison::hic15_difference);
  std::fprintf(out,
               "\nTable 1 over %zu pairs (medians: the mean of the middle two for an even count)\n"
               "%-8s %12s %12s %9s %10s %12s %11s %10s %10s\n",
               pairs.size(), "pair", "ref CPU [s]", "run CPU [s]", "CPU gain", "of ideal",
               "coordinator", "run wall", "wall gain", "HIC15");
  auto line = [&](const std::string& name, const Comparison& c, double ideal_fraction) {
    const std::string hic =
        c.has_head ? fmt::format("{:+.2f} %", 100.0 * c.hic15_difference) : std::string("-");
    std::fprintf(out, "%-8s %12.2f %12.2f %9.3f %8.1f %% %10.2f %% %9.2f s %10.3f %10s\n",
                 name.c_str(), c.cpu_reference_s, c.cpu_run_s, c.gain, 100.0 * ideal_fraction,
                 100.0 * c.coordinator_share, c.wall_run_s, c.wall_gain, hic.c_str());
  };
  for (std::size_t i = 0; i < pairs.size(); ++i)
    line(fmt::format("{}", i + 1), pairs[i], of_ideal[i]);
  line("median", m, median(of_ideal));
  std::fprintf(out, "ideal gain from element counts and steps: %.3f (median)\n", m.ideal_gain);
  std::fflush(out);
  return m;
}

int run_compare(const CompareOptions& options) {
  if (options.files.size() % 2 != 0) {
    throw InputError(fmt::format(
        "compare: {} files given; give them in pairs, each reference (mono) result.h5 followed "
        "by the run compared with it",
        options.files.size()));
  }
  std::vector<Comparison> pairs;
  for (std::size_t i = 0; i < options.files.size(); i += 2) {
    CompareOptions one = options;
    one.reference = options.files[i];
    one.run = options.files[i + 1];
    if (i > 0) std::printf("\n");
    pairs.push_back(compare_runs(one));
  }
  if (pairs.size() > 1) print_medians(pairs);
  return 0;
}

}  // namespace crashlink::apps
