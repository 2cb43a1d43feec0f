#include "solver/io/result_replay.h"

#include <fmt/format.h>

#include <vector>

#include "core/errors.h"
#include "solver/io/result_reader.h"

namespace crashlink::io {

namespace {

std::size_t rows_before(const std::vector<double>& t, double before_s) {
  std::size_t k = 0;
  while (k < t.size() && t[k] < before_s) ++k;
  return k;
}

}  // namespace

ReplayCounts replay_results(const std::string& from, ResultWriter& to, const model::Model& model,
                            double before_s) {
  const ResultReader in(from);
  ReplayCounts counts;

  auto glstat = in.glstat();
  std::vector<GlstatSample> rows;
  for (const auto& g : glstat)
    if (g.time_s < before_s) rows.push_back(g);
  to.append_glstat_rows(rows);
  counts.glstat_rows = rows.size();

  for (std::size_t p = 0; p < model.probes.size(); ++p) {
    const ProbeHistory h = in.probe(result_link_name(model.probes[p].name, "probe", p));
    const std::size_t k = rows_before(h.time_s, before_s);
    to.append_probe_rows(p, std::span<const double>(h.time_s.data(), k), probe_samples(h, k));
    counts.probe_rows += k;
  }

  for (std::size_t c = 0; c < model.contacts.size(); ++c) {
    const ContactHistory h = in.contact(result_link_name(model.contacts[c].name, "contact", c));
    const std::size_t k = rows_before(h.time_s, before_s);
    to.append_contact_rows(c, std::span<const double>(h.time_s.data(), k), contact_samples(h, k));
    counts.contact_rows += k;
  }

  const auto wall_names = in.wall_names();  // none in files written before 2026-11-27
  for (std::size_t w = 0; w < model.rigid_walls.size() && !wall_names.empty(); ++w) {
    const ContactHistory h = in.wall(result_link_name(model.rigid_walls[w].name, "rigid wall", w));
    const std::size_t k = rows_before(h.time_s, before_s);
    to.append_wall_rows(w, std::span<const double>(h.time_s.data(), k), contact_samples(h, k));
  }

  for (std::size_t s = 0; s < in.state_count(); ++s) {
    if (!(in.state_time(s) < before_s)) break;
    const StateData st = in.state(s);
    FieldState fs;
    fs.time_s = st.time_s;
    fs.displacement_m = st.displacement_m;
    fs.velocity_m_s = st.velocity_m_s;
    if (!st.parts.empty()) {
      for (std::size_t p = 0; p < model.parts.size(); ++p) {
        const std::string link = result_link_name(model.parts[p].name, "part", p);
        const PartStateData* found = nullptr;
        for (const auto& ps : st.parts)
          if (ps.link == link) found = &ps;
        if (found == nullptr) {
          throw InputError(
              fmt::format("{}: field state {} has no results for part '{}'; the "
                          "file was not written for this model",
                          from, s, model.parts[p].name));
        }
        fs.parts.push_back(PartFieldState{found->eps_p, found->von_mises_Pa, found->stress_Pa});
      }
    }
    to.write_field_state(fs);
    ++counts.states;
  }
  to.flush();
  return counts;
}

}  // namespace crashlink::io
