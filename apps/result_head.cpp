#include "apps/result_head.h"

#include <fmt/format.h>

#include <fstream>

#include "core/errors.h"

namespace crashlink::apps {

std::string first_rigid_body_probe(const io::ResultReader& reader) {
  for (const auto& name : reader.probe_names())
    if (reader.probe(name).kind == "rigid_body") return name;
  return {};
}

signal::HeadMetrics result_head_metrics(const io::ResultReader& reader, const std::string& h5,
                                        const std::string& probe) {
  const io::ProbeHistory p = reader.probe(probe);
  return signal::head_metrics_xyz(p.time_s, p.acceleration_m_s2, 1000,
                                  fmt::format("{}, probe '{}'", h5, probe));
}

void write_head_csv(const std::string& path, const signal::HeadMetrics& m, const char* who) {
  std::ofstream f(path);
  f << "time_ms,accel_g\n";
  for (std::size_t i = 0; i < m.time_s.size(); ++i)
    f << fmt::format("{:.6f},{:.6g}\n", 1e3 * m.time_s[i], m.accel_g[i]);
  f.close();
  if (!f) throw InputError(fmt::format("{}: cannot write {}", who, path));
}

}  // namespace crashlink::apps
