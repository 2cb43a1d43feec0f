// Gathered field states (state_merge.h).
#include "solver/gather/state_merge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "solver/gather/history_merge.h"

namespace crashlink::gather {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Index of the time in `times` (ascending, non-empty) nearest to t.
std::size_t nearest(const std::vector<double>& times, double t) {
  const auto it = std::lower_bound(times.begin(), times.end(), t);
  if (it == times.begin()) return 0;
  if (it == times.end()) return times.size() - 1;
  const auto j = static_cast<std::size_t>(it - times.begin());
  return t - times[j - 1] <= times[j] - t ? j - 1 : j;
}

/// Element results of one global part in the state being assembled.
struct PartBuffers {
  std::vector<double> eps_p, von_mises, stress;  // [ne], [ne], [6ne]
  std::vector<std::uint8_t> filled;              // [ne] 1: some field came from a file
  bool has_eps = false, has_von_mises = false, has_stress = false;

  void reset(std::size_t ne) {
    eps_p.assign(ne, kNaN);
    von_mises.assign(ne, kNaN);
    stress.assign(6 * ne, kNaN);
    filled.assign(ne, 0);
    has_eps = has_von_mises = has_stress = false;
  }
  bool any() const { return has_eps || has_von_mises || has_stress; }
};

/// Copies one domain's part results into the global part's buffers through the element map.
void scatter_part(const io::PartStateData& in, const DomainFile::Part& map, PartBuffers& out) {
  const std::size_t ne = map.element.size();
  if (in.eps_p.size() == ne) {
    for (std::size_t e = 0; e < ne; ++e)
      out.eps_p[static_cast<std::size_t>(map.element[e])] = in.eps_p[e];
    out.has_eps = out.has_eps || ne > 0;
  }
  if (in.von_mises_Pa.size() == ne) {
    for (std::size_t e = 0; e < ne; ++e)
      out.von_mises[static_cast<std::size_t>(map.element[e])] = in.von_mises_Pa[e];
    out.has_von_mises = out.has_von_mises || ne > 0;
  }
  if (in.stress_Pa.size() == 6 * ne) {
    for (std::size_t e = 0; e < ne; ++e)
      for (std::size_t c = 0; c < 6; ++c)
        out.stress[6 * static_cast<std::size_t>(map.element[e]) + c] = in.stress_Pa[6 * e + c];
    out.has_stress = out.has_stress || ne > 0;
  }
  if (in.eps_p.size() == ne || in.von_mises_Pa.size() == ne || in.stress_Pa.size() == 6 * ne)
    for (const std::int32_t ge : map.element) out.filled[static_cast<std::size_t>(ge)] = 1;
}

}  // namespace

std::int64_t write_states(const model::Model& global, const std::vector<DomainFile>& files,
                          io::ResultWriter& writer, GatherReport& report) {
  std::vector<const DomainFile*> sources;
  for (const DomainFile& f : files) {
    if (!f.reader) continue;
    if (f.state_times.empty()) {
      report.notes.push_back(
          fmt::format("domain '{}' has no field state: its nodes and elements have no data in "
                      "/states",
                      f.name));
      continue;
    }
    sources.push_back(&f);
  }
  if (sources.empty()) {
    report.notes.push_back("no domain file has a field state: /states is empty");
    return 0;
  }
  const DomainFile* grid = sources.front();
  double t_end = std::numeric_limits<double>::infinity();
  for (const DomainFile* s : sources) {
    if (s->state_times.size() < grid->state_times.size()) grid = s;
    t_end = std::min(t_end, s->state_times.back());
  }

  // Owners: per source, the (file row, global node) pairs it provides.
  const std::size_t n = global.nodes.count();
  std::vector<int> owner(n, -1);
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> provides(sources.size());
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const DomainFile& f = *sources[s];
    for (std::size_t r = 0; r < f.row_global.size(); ++r) {
      const auto g = static_cast<std::size_t>(f.row_global[r]);
      if (!f.row_owned[r] || owner[g] >= 0) continue;
      owner[g] = static_cast<int>(s);
      provides[s].emplace_back(r, g);
    }
  }
  const auto orphans = static_cast<std::size_t>(std::count(owner.begin(), owner.end(), -1));
  if (orphans > 0) {
    report.notes.push_back(fmt::format(
        "{} of {} nodes have no owner among the domain files with field states: displacement 0, "
        "velocity NaN in /states",
        orphans, n));
  }

  std::vector<PartBuffers> parts(global.parts.size());
  std::vector<double> u(3 * n), v(3 * n);
  std::vector<std::string> state_failures;
  double spread = 0.0;
  std::size_t unfilled_max = 0;
  std::int64_t written = 0;
  for (const double t : grid->state_times) {
    if (t > end_with_margin(t_end)) break;
    std::fill(u.begin(), u.end(), 0.0);
    std::fill(v.begin(), v.end(), kNaN);
    bool any_velocity = false;
    for (std::size_t p = 0; p < parts.size(); ++p) parts[p].reset(global.parts[p].element_count());
    for (std::size_t s = 0; s < sources.size(); ++s) {
      const DomainFile& f = *sources[s];
      const std::size_t k = nearest(f.state_times, t);
      spread = std::max(spread, std::abs(f.state_times[k] - t));
      io::StateData sd;
      try {
        sd = f.reader->state(k);
      } catch (const Error& e) {
        state_failures.push_back(fmt::format("domain '{}' state {}: {}", f.name, k, e.what()));
        continue;
      }
      const std::size_t rows = f.row_global.size();
      if (sd.displacement_m.size() != 3 * rows) {
        state_failures.push_back(
            fmt::format("domain '{}' state {}: {} displacement values for {} "
                        "nodes",
                        f.name, k, sd.displacement_m.size(), rows));
        continue;
      }
      const bool with_velocity = sd.velocity_m_s.size() == 3 * rows;
      any_velocity = any_velocity || with_velocity;
      for (const auto& [r, g] : provides[s]) {
        for (std::size_t c = 0; c < 3; ++c) {
          u[3 * g + c] = sd.displacement_m[3 * r + c];
          if (with_velocity) v[3 * g + c] = sd.velocity_m_s[3 * r + c];
        }
      }
      for (const io::PartStateData& ps : sd.parts) {
        const auto map = std::find_if(f.parts.begin(), f.parts.end(),
                                      [&](const DomainFile::Part& p) { return p.link == ps.link; });
        if (map == f.parts.end()) continue;  // results of a part the mesh does not list
        scatter_part(ps, *map, parts[static_cast<std::size_t>(map->global_part)]);
      }
    }
    io::FieldState state;
    state.time_s = t;
    state.displacement_m = u;
    if (any_velocity) state.velocity_m_s = v;
    const bool any_part =
        std::any_of(parts.begin(), parts.end(), [](const PartBuffers& b) { return b.any(); });
    std::size_t unfilled = 0;
    if (any_part) {
      for (const PartBuffers& b : parts) {
        io::PartFieldState pf;
        if (b.has_eps) pf.eps_p = b.eps_p;
        if (b.has_von_mises) pf.von_mises_Pa = b.von_mises;
        if (b.has_stress) pf.stress_Pa = b.stress;
        if (b.any())
          unfilled += static_cast<std::size_t>(std::count(b.filled.begin(), b.filled.end(), 0));
        state.parts.push_back(pf);
      }
    }
    unfilled_max = std::max(unfilled_max, unfilled);
    writer.write_field_state(state);
    ++written;
  }
  if (!state_failures.empty()) {
    report.notes.push_back(
        fmt::format("{} domain field state(s) unreadable, their values missing "
                    "from the gathered state (first: {})",
                    state_failures.size(), state_failures.front()));
  }
  if (unfilled_max > 0) {
    report.notes.push_back(
        fmt::format("up to {} elements per state have no element results "
                    "(their domain file is missing): NaN in /states",
                    unfilled_max));
  }
  if (spread > 0.0) {
    report.notes.push_back(
        fmt::format("field states matched across domains by nearest time: "
                    "largest time difference {:.3e} s",
                    spread));
  }
  for (const DomainFile* s : sources) {
    if (s->state_times.size() > static_cast<std::size_t>(written)) {
      report.notes.push_back(
          fmt::format("field states stop at t = {:.6e} s (the last state of the "
                      "shortest domain file); domain '{}' has {} states, {} "
                      "gathered",
                      t_end, s->name, s->state_times.size(), written));
    }
  }
  return written;
}

}  // namespace crashlink::gather
