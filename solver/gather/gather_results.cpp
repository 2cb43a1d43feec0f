// The gather of a coupled run's per-domain result files into DIR/result.h5 (gather_results.h).
#include "solver/gather/gather_results.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

#include "core/errors.h"
#include "solver/gather/coordinator_file.h"
#include "solver/gather/domain_files.h"
#include "solver/gather/history_merge.h"
#include "solver/gather/state_merge.h"
#include "solver/io/result_writer.h"

namespace crashlink::gather {

namespace {

/// The domain file holding the item `name` of the sub-models (probes or contacts), or nullptr.
template <class Items>
const DomainFile* holder(const partition::Decomposition& dec, const std::vector<DomainFile>& files,
                         const std::string& name, Items items) {
  for (const DomainFile& f : files) {
    const auto& list = items(dec.domains[static_cast<std::size_t>(f.domain)].model);
    if (std::any_of(list.begin(), list.end(), [&](const auto& x) { return x.name == name; }))
      return &f;
  }
  return nullptr;
}

/// Rows of `times` not after t_cut (times ascending).
std::size_t rows_until(const std::vector<double>& times, double t_cut) {
  return static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t_cut) -
                                  times.begin());
}

/// /history/glstat: the summed, interpolated energies; returns the cut time for the other
/// histories (+inf if there is no glstat).
double write_glstat(const std::vector<DomainFile>& files, io::ResultWriter& writer,
                    GatherReport& report) {
  std::vector<std::vector<io::GlstatSample>> series;
  std::vector<std::string> without;
  double last_max = -std::numeric_limits<double>::infinity();
  for (const DomainFile& f : files) {
    series.push_back(f.reader ? f.glstat : std::vector<io::GlstatSample>{});
    if (series.back().empty())
      without.push_back(f.name);
    else
      last_max = std::max(last_max, series.back().back().time_s);
  }
  if (!without.empty()) {
    report.notes.push_back(
        fmt::format("/history/glstat lacks the energies of domain(s) {} (no "
                    "history in their file)",
                    fmt::join(without, ", ")));
  }
  const GlstatMerge merge = merge_glstat(series);
  if (merge.rows.empty()) {
    report.notes.push_back("no domain file has a glstat history: /history is empty");
    return std::numeric_limits<double>::infinity();
  }
  writer.append_glstat_rows(merge.rows);
  report.history_samples = static_cast<std::int64_t>(merge.rows.size());
  report.end_time_s = merge.rows.back().time_s;
  // A domain that stopped more than one grid interval before another: a failed or killed daemon.
  const auto& grid = series[merge.grid];
  const double spacing =
      grid.size() >= 2 ? grid[grid.size() - 1].time_s - grid[grid.size() - 2].time_s : 0.0;
  if (last_max - merge.end_time_s > spacing) {
    for (std::size_t s = 0; s < series.size(); ++s) {
      if (!series[s].empty() && series[s].back().time_s == merge.end_time_s) {
        report.notes.push_back(fmt::format(
            "the history of domain '{}' ends at t = {:.6e} s, others run to {:.6e} s (the run "
            "failed or the daemon stopped early): the gathered histories stop at {:.6e} s",
            files[s].name, merge.end_time_s, last_max, report.end_time_s));
      }
    }
  }
  return end_with_margin(merge.end_time_s);
}

void write_probes(const model::Model& global, const partition::Decomposition& dec,
                  const std::vector<DomainFile>& files, double t_cut, io::ResultWriter& writer,
                  GatherReport& report) {
  for (std::size_t i = 0; i < global.probes.size(); ++i) {
    const std::string& name = global.probes[i].name;
    const DomainFile* f = holder(
        dec, files, name, [](const model::Model& m) -> const auto& { return m.probes; });
    if (f == nullptr) {
      report.notes.push_back(
          fmt::format("probe '{}' is in no domain of the decomposition: no rows", name));
      continue;
    }
    if (!f->reader) {
      report.notes.push_back(
          fmt::format("probe '{}': its domain '{}' has no usable file: no rows", name, f->name));
      continue;
    }
    io::ProbeHistory h;
    try {
      h = f->reader->probe(name);
    } catch (const Error& e) {
      report.notes.push_back(
          fmt::format("probe '{}': not read from domain '{}': {}", name, f->name, e.what()));
      continue;
    }
    const std::size_t k = rows_until(h.time_s, t_cut);
    writer.append_probe_rows(i, std::span<const double>(h.time_s.data(), k),
                             io::probe_samples(h, k));
  }
}

/// into += from, from's rows linearly interpolated at into's times (held at its ends).
void add_interpolated(const io::ContactHistory& from, io::ContactHistory& into) {
  if (from.time_s.empty()) return;
  const bool energy = !from.energy_J.empty() && !into.energy_J.empty();
  for (std::size_t r = 0; r < into.time_s.size(); ++r) {
    const double t = into.time_s[r];
    auto it = std::lower_bound(from.time_s.begin(), from.time_s.end(), t);
    std::size_t b = static_cast<std::size_t>(it - from.time_s.begin());
    std::size_t a = b;
    double w = 0.0;
    if (b >= from.time_s.size()) {
      a = b = from.time_s.size() - 1;
    } else if (b > 0 && from.time_s[b] != t) {
      a = b - 1;
      w = (t - from.time_s[a]) / (from.time_s[b] - from.time_s[a]);
    } else {
      a = b;
    }
    for (std::size_t d = 0; d < 3; ++d)
      into.force_N[3 * r + d] += (1.0 - w) * from.force_N[3 * a + d] + w * from.force_N[3 * b + d];
    if (energy) into.energy_J[r] += (1.0 - w) * from.energy_J[a] + w * from.energy_J[b];
  }
}

void write_contacts(const model::Model& global, const partition::Decomposition& dec,
                    const std::vector<DomainFile>& files, double t_cut, io::ResultWriter& writer,
                    GatherReport& report) {
  for (std::size_t i = 0; i < global.contacts.size(); ++i) {
    const std::string& name = global.contacts[i].name;
    const DomainFile* f = holder(
        dec, files, name, [](const model::Model& m) -> const auto& { return m.contacts; });
    if (f == nullptr || !f->reader) {
      report.notes.push_back(fmt::format(
          "contact '{}': {}: no rows", name,
          f == nullptr ? std::string("in no domain") : "domain '" + f->name + "' missing"));
      continue;
    }
    io::ContactHistory h;
    try {
      h = f->reader->contact(name);
    } catch (const Error& e) {
      report.notes.push_back(
          fmt::format("contact '{}': not read from domain '{}': {}", name, f->name, e.what()));
      continue;
    }
    // A single-surface contact is computed in every domain holding its parts (each over its own
    // elements): the force and energy are the sums, the others' rows interpolated linearly in
    // time onto the first holder's.
    if (global.contacts[i].kind == model::ContactKind::SingleSurface)
      for (const DomainFile& o : files) {
        if (&o == f || !o.reader) continue;
        const auto& list = dec.domains[static_cast<std::size_t>(o.domain)].model.contacts;
        if (std::none_of(list.begin(), list.end(), [&](const auto& x) { return x.name == name; }))
          continue;
        io::ContactHistory other;
        try {
          other = o.reader->contact(name);
        } catch (const Error& e) {
          report.notes.push_back(
              fmt::format("contact '{}': domain '{}' not added: {}", name, o.name, e.what()));
          continue;
        }
        add_interpolated(other, h);
      }
    const std::size_t k = rows_until(h.time_s, t_cut);
    writer.append_contact_rows(i, std::span<const double>(h.time_s.data(), k),
                               io::contact_samples(h, k));
  }
}

/// /history/rigid_walls: a wall whose nodes lie in several domains is applied in each to its own
/// nodes (partition::sub_model): its force and work are the sums, the other holders' rows
/// interpolated in time onto the first's.
void write_walls(const model::Model& global, const partition::Decomposition& dec,
                 const std::vector<DomainFile>& files, double t_cut, io::ResultWriter& writer,
                 GatherReport& report) {
  for (std::size_t i = 0; i < global.rigid_walls.size(); ++i) {
    const std::string& name = global.rigid_walls[i].name;
    std::optional<io::ContactHistory> sum;
    for (const DomainFile& f : files) {
      const auto& list = dec.domains[static_cast<std::size_t>(f.domain)].model.rigid_walls;
      if (!f.reader ||
          std::none_of(list.begin(), list.end(), [&](const auto& x) { return x.name == name; }))
        continue;
      io::ContactHistory h;
      try {
        h = f.reader->wall(name);
      } catch (const Error& e) {
        report.notes.push_back(
            fmt::format("rigid wall '{}': not read from domain '{}': {}", name, f.name, e.what()));
        continue;
      }
      if (!sum)
        sum = std::move(h);
      else
        add_interpolated(h, *sum);
    }
    if (!sum) {
      report.notes.push_back(fmt::format("rigid wall '{}': no rows", name));
      continue;
    }
    const std::size_t k = rows_until(sum->time_s, t_cut);
    writer.append_wall_rows(i, std::span<const double>(sum->time_s.data(), k),
                            io::contact_samples(*sum, k));
  }
}

/// /timing/<domain> of every domain file that has one.
std::vector<io::DomainTiming> domain_timings(const std::vector<DomainFile>& files,
                                             GatherReport& report) {
  std::vector<io::DomainTiming> out;
  for (const DomainFile& f : files) {
    if (!f.reader) continue;
    io::TimingData t;
    try {
      t = f.reader->timing();
    } catch (const Error& e) {
      report.notes.push_back(
          fmt::format("domain '{}': /timing unreadable, not copied: {}", f.name, e.what()));
      continue;
    }
    auto it = std::find_if(t.domains.begin(), t.domains.end(),
                           [&](const io::DomainTiming& d) { return d.name == f.name; });
    if (it == t.domains.end() && t.domains.size() == 1) it = t.domains.begin();
    if (it == t.domains.end()) {
      report.notes.push_back(fmt::format(
          "domain '{}' wrote no /timing (the daemon did not finish): no /timing/{} entry", f.name,
          f.name));
      continue;
    }
    io::DomainTiming d = *it;
    d.name = f.name;
    out.push_back(d);
  }
  return out;
}

/// Every domain's spot weld failures, in time order (a weld is in one domain).
std::vector<io::SpotWeldFailure> spot_weld_failures(const std::vector<DomainFile>& files) {
  std::vector<io::SpotWeldFailure> out;
  for (const auto& f : files)
    if (f.reader)
      for (auto& w : f.reader->spot_weld_failures()) out.push_back(std::move(w));
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  return out;
}

}  // namespace

GatherReport gather_results(const model::Model& global, const partition::Decomposition& dec,
                            const std::string& out_dir) {
  GatherReport report;
  const std::vector<DomainFile> files = open_domain_files(global, dec, out_dir, report);
  const CoordinatorTiming coordinator = read_coordinator_timing(out_dir, report);

  io::ResultWriter writer(out_dir, global);
  const double t_cut = write_glstat(files, writer, report);
  write_probes(global, dec, files, t_cut, writer, report);
  write_contacts(global, dec, files, t_cut, writer, report);
  write_walls(global, dec, files, t_cut, writer, report);
  report.states = write_states(global, files, writer, report);
  writer.write_timing(coordinator.wall_seconds, coordinator.coordinator_cpu_seconds,
                      domain_timings(files, report));
  writer.write_spot_weld_failures(spot_weld_failures(files));
  const std::string h5 = writer.h5_path();
  writer.close();

  std::map<std::string, std::string> names;  // /timing/<link> -> domain name
  for (std::size_t d = 0; d < dec.domains.size(); ++d)
    names[io::result_link_name(dec.domains[d].name, "domain", d)] = dec.domains[d].name;
  finish_result_file(h5, out_dir, coordinator, names, report);
  return report;
}

}  // namespace crashlink::gather
