#include "apps/timing_reader.h"

#include <hdf5.h>

namespace crashlink::apps {

namespace {

template <typename T>
bool read_attribute(hid_t object, const char* name, hid_t type, T& out) {
  if (H5Aexists(object, name) <= 0) return false;
  const hid_t a = H5Aopen(object, name, H5P_DEFAULT);
  if (a < 0) return false;
  const bool ok = H5Aread(a, type, &out) >= 0;
  H5Aclose(a);
  return ok;
}

std::string read_string_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return {};
  const hid_t a = H5Aopen(object, name, H5P_DEFAULT);
  if (a < 0) return {};
  std::string out;
  const hid_t stored = H5Aget_type(a);
  if (H5Tis_variable_str(stored) > 0) {
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    char* text = nullptr;
    if (H5Aread(a, t, &text) >= 0 && text != nullptr) {
      out = text;
      H5free_memory(text);
    }
    H5Tclose(t);
  }
  H5Tclose(stored);
  H5Aclose(a);
  return out;
}

herr_t collect(hid_t group, const char* name, const H5L_info_t*, void* data) {
  auto& record = *static_cast<TimingRecord*>(data);
  const hid_t g = H5Gopen2(group, name, H5P_DEFAULT);
  if (g < 0) return 0;
  io::DomainTiming d;
  d.name = read_string_attribute(g, "name");
  if (d.name.empty()) d.name = name;
  read_attribute(g, "cpu_seconds", H5T_NATIVE_DOUBLE, d.cpu_seconds);
  read_attribute(g, "dt_min", H5T_NATIVE_DOUBLE, d.dt_min_s);
  read_attribute(g, "cycles", H5T_NATIVE_INT64, d.cycles);
  read_attribute(g, "elements", H5T_NATIVE_INT64, d.elements);
  read_attribute(g, "threads", H5T_NATIVE_INT64, d.threads);                   // absent: 1
  read_attribute(g, "contact_seconds", H5T_NATIVE_DOUBLE, d.contact_seconds);  // absent: 0
  read_attribute(g, "contact_node_cycles", H5T_NATIVE_INT64, d.contact_node_cycles);
  read_attribute(g, "peak_rss_bytes", H5T_NATIVE_INT64, d.peak_rss_bytes);
  read_attribute(g, "setup_cpu_seconds", H5T_NATIVE_DOUBLE, d.setup_cpu_seconds);
  H5Gclose(g);
  record.domains.push_back(std::move(d));
  return 0;
}

}  // namespace

std::optional<TimingRecord> read_timing(const std::string& h5_path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return std::nullopt;
  std::optional<TimingRecord> r;
  if (H5Lexists(f, "/timing", H5P_DEFAULT) > 0) {
    const hid_t g = H5Gopen2(f, "/timing", H5P_DEFAULT);
    if (g >= 0) {
      TimingRecord t;
      read_attribute(g, "wall_seconds", H5T_NATIVE_DOUBLE, t.wall_seconds);
      read_attribute(g, "coordinator_cpu_seconds", H5T_NATIVE_DOUBLE, t.coordinator_cpu_seconds);
      H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &t);
      H5Gclose(g);
      r = std::move(t);
    }
  }
  H5Fclose(f);
  return r;
}

}  // namespace crashlink::apps
