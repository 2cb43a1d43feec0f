#include "apps/contact_force_csv.h"

#include <fmt/format.h>

#include <cstdio>
#include <fstream>

#include "core/errors.h"
#include "solver/signal/channel_filter.h"

namespace crashlink::apps {

namespace {

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

}  // namespace

void write_contact_force_csv(const std::string& path, const io::ResultReader& reader,
                             const char* who) {
  std::ofstream f(path);
  f << "contact,filter,time_ms,force_kN\n";
  for (const std::string& name : reader.contact_names()) {
    const io::ContactHistory h = reader.contact(name);
    if (h.size() == 0) continue;
    std::vector<double> time_s = h.time_s, force_kN;
    std::string filter = fmt::format("CFC {}", signal::kStructuralForceCfc);
    try {
      const signal::FilteredChannels c =
          signal::filter_channels(h.time_s, signal::xyz_channels(h.force_N),
                                  signal::kStructuralForceCfc, fmt::format("contact '{}'", name));
      time_s = c.time_s;
      force_kN = signal::channel_resultant(c.channels, 1e-3);
    } catch (const InputError& e) {
      std::fprintf(stderr, "%s: contact '%s' plotted unfiltered: %s\n", who, name.c_str(),
                   e.what());
      filter = "none";
      force_kN = signal::channel_resultant(signal::xyz_channels(h.force_N), 1e-3);
    }
    const std::string field = csv_field(name);
    for (std::size_t i = 0; i < time_s.size(); ++i)
      f << fmt::format("{},{},{:.9g},{:.9g}\n", field, filter, 1e3 * time_s[i], force_kN[i]);
  }
  f.close();
  if (!f) throw InputError(fmt::format("{}: cannot write {}", who, path));
}

}  // namespace crashlink::apps
