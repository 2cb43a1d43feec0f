#include "solver/io/result_reader.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

#include "solver/io/hdf5_handles.h"

namespace crashlink::io {

namespace {

// H5S_ALL expands to a C-style cast; -Wold-style-cast is silenced for this definition only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
constexpr hid_t kAll = H5S_ALL;
#pragma GCC diagnostic pop

[[noreturn]] void fail(const Location& at, const std::string& object, const std::string& what) {
  throw ResultFileError(at.file, object, what);
}

/// A whole rank-1 int64 dataset `name` under `at`.
std::vector<std::int64_t> read_int64s(const Location& at, const std::string& name) {
  const std::string object = at.child(name);
  if (!link_exists(at, name)) {
    fail(at, object, "dataset missing (the file does not follow docs/result-format.md)");
  }
  DatasetHandle ds(H5Dopen2(at.id, name.c_str(), H5P_DEFAULT));
  if (!ds) fail(at, object, "H5Dopen2 (open dataset)");
  DataspaceHandle space(H5Dget_space(ds.get()));
  if (!space) fail(at, object, "H5Dget_space");
  hsize_t dims[1] = {0};
  if (H5Sget_simple_extent_ndims(space.get()) != 1 ||
      H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0) {
    fail(at, object, "shape is not [k] (docs/result-format.md)");
  }
  std::vector<std::int64_t> out(dims[0]);
  if (!out.empty() &&
      H5Dread(ds.get(), H5T_NATIVE_INT64, kAll, kAll, H5P_DEFAULT, out.data()) < 0) {
    fail(at, object, "H5Dread");
  }
  return out;
}

/// A scalar numeric attribute read as `memory_type`; nullopt if absent.
template <class T>
std::optional<T> read_number_attribute(const Location& at, const std::string& name,
                                       hid_t memory_type) {
  const std::string object = at.path + "@" + name;
  const htri_t exists = H5Aexists(at.id, name.c_str());
  if (exists < 0) fail(at, object, "H5Aexists");
  if (exists == 0) return std::nullopt;
  AttributeHandle a(H5Aopen(at.id, name.c_str(), H5P_DEFAULT));
  if (!a) fail(at, object, "H5Aopen");
  T value{};
  if (H5Aread(a.get(), memory_type, &value) < 0) fail(at, object, "H5Aread");
  return value;
}

/// A scalar string attribute (variable or fixed length); nullopt if absent.
std::optional<std::string> read_string_attribute(const Location& at, const std::string& name) {
  const std::string object = at.path + "@" + name;
  const htri_t exists = H5Aexists(at.id, name.c_str());
  if (exists < 0) fail(at, object, "H5Aexists");
  if (exists == 0) return std::nullopt;
  AttributeHandle a(H5Aopen(at.id, name.c_str(), H5P_DEFAULT));
  if (!a) fail(at, object, "H5Aopen");
  DatatypeHandle file_type(H5Aget_type(a.get()));
  if (!file_type || H5Tget_class(file_type.get()) != H5T_STRING) return std::nullopt;
  const htri_t variable = H5Tis_variable_str(file_type.get());
  if (variable < 0) fail(at, object, "H5Tis_variable_str");
  DatatypeHandle memory_type(H5Tcopy(file_type.get()));
  if (!memory_type) fail(at, object, "H5Tcopy");
  if (variable > 0) {
    char* value = nullptr;
    if (H5Aread(a.get(), memory_type.get(), &value) < 0) fail(at, object, "H5Aread");
    std::string s = value ? value : "";
    H5free_memory(value);
    return s;
  }
  const std::size_t size = H5Tget_size(file_type.get());
  std::string s(size, '\0');
  if (H5Aread(a.get(), memory_type.get(), s.data()) < 0) fail(at, object, "H5Aread");
  s.resize(std::min(s.size(), s.find('\0')));
  return s;
}

/// The link names directly under a group, in name order.
std::vector<std::string> child_names(const Location& at) {
  H5G_info_t info;
  if (H5Gget_info(at.id, &info) < 0) fail(at, at.path, "H5Gget_info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(at.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) fail(at, at.path, "H5Lget_name_by_idx");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    if (H5Lget_name_by_idx(at.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                           H5P_DEFAULT) < 0) {
      fail(at, at.path, "H5Lget_name_by_idx");
    }
    name.resize(static_cast<std::size_t>(len));
    names.push_back(std::move(name));
  }
  return names;
}

/// The /history/glstat columns in GlstatSample order; `required` per docs/design.md §4.
struct GlstatColumn {
  const char* name;
  double GlstatSample::*value;
  bool required;
};
constexpr std::array<GlstatColumn, 11> kGlstat{{
    {"time", &GlstatSample::time_s, true},
    {"kinetic_energy", &GlstatSample::kinetic_energy_J, true},
    {"internal_energy", &GlstatSample::internal_energy_J, true},
    {"hourglass_energy", &GlstatSample::hourglass_energy_J, true},
    {"contact_energy", &GlstatSample::contact_energy_J, true},
    {"external_work", &GlstatSample::external_work_J, true},
    {"total_energy", &GlstatSample::total_energy_J, true},
    {"energy_balance_error", &GlstatSample::energy_balance_error, false},
    {"coupling_work", &GlstatSample::coupling_work_J, false},  // files before 2026-11-21: 0
    {"scheme_energy", &GlstatSample::scheme_energy_J, false},  // before 2026-11-28: NaN
    {"scheme_energy_time", &GlstatSample::scheme_energy_time_s, false},
}};

}  // namespace

struct ResultReader::Impl {
  FileHandle file;
  std::string h5_path;
  struct ProbeEntry {
    std::string name, link;
  };
  std::vector<ProbeEntry> probes;    // in link order
  std::vector<ProbeEntry> contacts;  // in link order
  std::vector<ProbeEntry> walls;     // /history/rigid_walls, in link order

  /// The group at absolute path `object`; throws ResultFileError saying what is missing.
  GroupHandle group(const std::string& object, const char* what) const {
    GroupHandle g(H5Gopen2(file.get(), object.c_str(), H5P_DEFAULT));
    if (!g) fail(root(), object, fmt::format("H5Gopen2 (open group; {})", what));
    return g;
  }

  Location root() const { return Location{file.get(), h5_path, "/"}; }
  std::string probe_path(const std::string& link) const { return "/history/probes/" + link; }
};

ResultReader::ResultReader(const std::string& h5_path) : path_(h5_path) {
  auto impl = std::make_unique<Impl>();
  impl->h5_path = h5_path;
  impl->file = open_file_read(h5_path);
  const Location root = impl->root();
  const auto format = read_string_attribute(root, "format");
  if (format != std::optional<std::string>("crashlink-result")) {
    fail(root, "/",
         fmt::format("not a crashlink result file (root attribute format = '{}', expected "
                     "'crashlink-result'); give the result.h5 that `crashlink run` wrote",
                     format.value_or("<absent>")));
  }
  if (link_exists(root, "history")) {
    GroupHandle history = open_group(root, "history");
    const Location hat{history.get(), h5_path, "/history"};
    if (link_exists(hat, "probes")) {
      GroupHandle probes = open_group(hat, "probes");
      const Location pat{probes.get(), h5_path, "/history/probes"};
      for (const std::string& link : child_names(pat)) {
        GroupHandle g = open_group(pat, link);
        const Location at{g.get(), h5_path, pat.child(link)};
        impl->probes.push_back(
            Impl::ProbeEntry{read_string_attribute(at, "name").value_or(link), link});
      }
    }
    for (const auto& [group, list] :
         {std::pair{"contacts", &impl->contacts}, std::pair{"rigid_walls", &impl->walls}}) {
      if (!link_exists(hat, group)) continue;
      GroupHandle gr = open_group(hat, group);
      const Location cat{gr.get(), h5_path, std::string("/history/") + group};
      for (const std::string& link : child_names(cat)) {
        GroupHandle g = open_group(cat, link);
        const Location at{g.get(), h5_path, cat.child(link)};
        list->push_back(Impl::ProbeEntry{read_string_attribute(at, "name").value_or(link), link});
      }
    }
  }
  impl_ = std::move(impl);
}

ResultReader::ResultReader(ResultReader&&) noexcept = default;
ResultReader& ResultReader::operator=(ResultReader&&) noexcept = default;
ResultReader::~ResultReader() = default;

std::string ResultReader::model_name() const {
  return read_string_attribute(impl_->root(), "model").value_or("");
}

std::vector<std::string> ResultReader::probe_names() const {
  std::vector<std::string> names;
  for (const auto& p : impl_->probes) names.push_back(p.name);
  return names;
}

bool ResultReader::has_probe(const std::string& name) const {
  return std::any_of(impl_->probes.begin(), impl_->probes.end(),
                     [&](const Impl::ProbeEntry& p) { return p.name == name || p.link == name; });
}

ProbeHistory ResultReader::probe(const std::string& name) const {
  auto it = std::find_if(impl_->probes.begin(), impl_->probes.end(),
                         [&](const Impl::ProbeEntry& p) { return p.name == name; });
  if (it == impl_->probes.end()) {
    it = std::find_if(impl_->probes.begin(), impl_->probes.end(),
                      [&](const Impl::ProbeEntry& p) { return p.link == name; });
  }
  if (it == impl_->probes.end()) {
    const std::vector<std::string> names = probe_names();
    throw InputError(fmt::format(
        "{}: no probe named '{}'; the file has {}{}", path_, name,
        names.empty() ? std::string("no probes (the scenario named none)")
                      : fmt::format("{} probe(s): {}", names.size(), fmt::join(names, ", ")),
        names.empty() ? "" : " (pass one of them to --probe)"));
  }
  const std::string object = impl_->probe_path(it->link);
  GroupHandle g(H5Gopen2(impl_->file.get(), object.c_str(), H5P_DEFAULT));
  if (!g) fail(impl_->root(), object, "H5Gopen2 (open group)");
  const Location at{g.get(), impl_->h5_path, object};
  ProbeHistory h;
  h.name = it->name;
  h.link = it->link;
  h.kind = read_string_attribute(at, "kind").value_or("");
  std::array<std::size_t, 4> rows{};
  h.time_s = read_doubles(at, "time", 0, &rows[0]);
  h.displacement_m = read_doubles(at, "displacement", 3, &rows[1]);
  h.velocity_m_s = read_doubles(at, "velocity", 3, &rows[2]);
  h.acceleration_m_s2 = read_doubles(at, "acceleration", 3, &rows[3]);
  const std::size_t k = *std::min_element(rows.begin(), rows.end());  // common prefix
  h.time_s.resize(k);
  h.displacement_m.resize(3 * k);
  h.velocity_m_s.resize(3 * k);
  h.acceleration_m_s2.resize(3 * k);
  return h;
}

std::vector<GlstatSample> ResultReader::glstat() const {
  const std::string object = "/history/glstat";
  GroupHandle g(H5Gopen2(impl_->file.get(), object.c_str(), H5P_DEFAULT));
  if (!g) fail(impl_->root(), object, "H5Gopen2 (open group; the file has no glstat history)");
  const Location at{g.get(), impl_->h5_path, object};
  std::array<std::vector<double>, kGlstat.size()> columns;
  std::size_t k = static_cast<std::size_t>(-1);
  for (std::size_t c = 0; c < kGlstat.size(); ++c) {
    if (!kGlstat[c].required && !link_exists(at, kGlstat[c].name)) continue;
    std::size_t rows = 0;
    columns[c] = read_doubles(at, kGlstat[c].name, 0, &rows);
    k = std::min(k, rows);
  }
  std::vector<GlstatSample> out(k);
  for (std::size_t c = 0; c < kGlstat.size(); ++c) {
    if (columns[c].empty()) continue;
    for (std::size_t i = 0; i < k; ++i) out[i].*kGlstat[c].value = columns[c][i];
  }
  return out;
}

std::vector<std::string> ResultReader::contact_names() const {
  std::vector<std::string> names;
  for (const auto& c : impl_->contacts) names.push_back(c.name);
  return names;
}

ContactHistory ResultReader::contact(const std::string& name) const {
  return item_history(false, name);
}

std::vector<std::string> ResultReader::wall_names() const {
  std::vector<std::string> names;
  for (const auto& c : impl_->walls) names.push_back(c.name);
  return names;
}

ContactHistory ResultReader::wall(const std::string& name) const {
  return item_history(true, name);
}

ContactHistory ResultReader::item_history(bool wall, const std::string& name) const {
  const auto& list = wall ? impl_->walls : impl_->contacts;
  const char* what = wall ? "rigid wall" : "contact";
  auto it = std::find_if(list.begin(), list.end(),
                         [&](const Impl::ProbeEntry& c) { return c.name == name; });
  if (it == list.end()) {
    it = std::find_if(list.begin(), list.end(),
                      [&](const Impl::ProbeEntry& c) { return c.link == name; });
  }
  if (it == list.end()) {
    std::vector<std::string> names;
    for (const auto& c : list) names.push_back(c.name);
    throw InputError(fmt::format(
        "{}: no {} named '{}'; the file has {}", path_, what, name,
        names.empty() ? fmt::format("no {} histories", what)
                      : fmt::format("{} {}(s): {}", names.size(), what, fmt::join(names, ", "))));
  }
  const std::string object =
      std::string(wall ? "/history/rigid_walls/" : "/history/contacts/") + it->link;
  GroupHandle g = impl_->group(object, wall ? "rigid wall history" : "contact history");
  const Location at{g.get(), impl_->h5_path, object};
  ContactHistory h;
  h.name = it->name;
  h.link = it->link;
  std::array<std::size_t, 3> rows{};
  h.time_s = read_doubles(at, "time", 0, &rows[0]);
  h.force_N = read_doubles(at, "force", 3, &rows[1]);
  const char* third = wall ? "work" : "energy";
  const bool energy = link_exists(at, third);  // a contact's: absent in files before 2026-11-26
  if (energy) h.energy_J = read_doubles(at, third, 0, &rows[2]);
  const std::size_t k = std::min({rows[0], rows[1], energy ? rows[2] : rows[0]});  // common prefix
  h.time_s.resize(k);
  h.force_N.resize(3 * k);
  if (energy) h.energy_J.resize(k);
  return h;
}

std::vector<std::int64_t> ResultReader::node_ids() const {
  GroupHandle g = impl_->group("/mesh", "the file has no mesh");
  return read_int64s(Location{g.get(), impl_->h5_path, "/mesh"}, "node_ids");
}

std::vector<MeshPartInfo> ResultReader::mesh_parts() const {
  GroupHandle g = impl_->group("/mesh/parts", "the file has no mesh parts");
  const Location pat{g.get(), impl_->h5_path, "/mesh/parts"};
  std::vector<MeshPartInfo> out;
  for (const std::string& link : child_names(pat)) {
    GroupHandle pg = open_group(pat, link);
    const Location at{pg.get(), impl_->h5_path, pat.child(link)};
    MeshPartInfo p;
    p.link = link;
    p.name = read_string_attribute(at, "name").value_or(link);
    p.kind = read_string_attribute(at, "kind").value_or("");
    p.index = read_number_attribute<std::int64_t>(at, "index", H5T_NATIVE_INT64)
                  .value_or(static_cast<std::int64_t>(out.size()));
    p.id = read_number_attribute<std::int64_t>(at, "id", H5T_NATIVE_INT64).value_or(0);
    p.element_ids = read_int64s(at, "element_ids");
    out.push_back(std::move(p));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const MeshPartInfo& a, const MeshPartInfo& b) { return a.index < b.index; });
  return out;
}

std::vector<SpotWeldFailure> ResultReader::spot_weld_failures() const {
  std::vector<SpotWeldFailure> out;
  const Location root = impl_->root();
  if (!link_exists(root, "events")) return out;
  GroupHandle e = open_group(root, "events");
  const Location eat{e.get(), impl_->h5_path, "/events"};
  if (!link_exists(eat, "spot_weld_failures")) return out;
  GroupHandle g = open_group(eat, "spot_weld_failures");
  const Location at{g.get(), impl_->h5_path, "/events/spot_weld_failures"};
  const auto count = read_number_attribute<std::int64_t>(at, "count", H5T_NATIVE_INT64).value_or(0);
  for (std::int64_t k = 0; k < count; ++k) {
    const std::string link = std::to_string(k);
    GroupHandle fg = open_group(at, link);
    const Location fat{fg.get(), impl_->h5_path, at.child(link)};
    SpotWeldFailure f;
    f.name = read_string_attribute(fat, "name").value_or(link);
    f.time_s = read_number_attribute<double>(fat, "time", H5T_NATIVE_DOUBLE).value_or(0.0);
    f.tension_N = read_number_attribute<double>(fat, "tension", H5T_NATIVE_DOUBLE).value_or(0.0);
    f.shear_N = read_number_attribute<double>(fat, "shear", H5T_NATIVE_DOUBLE).value_or(0.0);
    out.push_back(std::move(f));
  }
  return out;
}

std::size_t ResultReader::state_count() const {
  const Location root = impl_->root();
  if (!link_exists(root, "states")) return 0;
  GroupHandle g = open_group(root, "states");
  const auto count = read_number_attribute<std::int64_t>(
      Location{g.get(), impl_->h5_path, "/states"}, "count", H5T_NATIVE_INT64);
  return count && *count > 0 ? static_cast<std::size_t>(*count) : 0;
}

double ResultReader::state_time(std::size_t k) const {
  const std::string object = fmt::format("/states/{}", k);
  GroupHandle g = impl_->group(object, "field state missing");
  const auto t = read_number_attribute<double>(Location{g.get(), impl_->h5_path, object}, "time",
                                               H5T_NATIVE_DOUBLE);
  if (!t) fail(impl_->root(), object + "@time", "attribute missing (incomplete field state)");
  return *t;
}

StateData ResultReader::state(std::size_t k) const {
  const std::string object = fmt::format("/states/{}", k);
  GroupHandle g = impl_->group(object, "field state missing");
  const Location at{g.get(), impl_->h5_path, object};
  StateData s;
  s.time_s = state_time(k);
  std::size_t rows = 0;
  s.displacement_m = read_doubles(at, "displacement", 3, &rows);
  if (link_exists(at, "velocity")) {
    std::size_t vrows = 0;
    s.velocity_m_s = read_doubles(at, "velocity", 3, &vrows);
    if (vrows != rows) fail(at, at.child("velocity"), "row count differs from displacement");
  }
  if (link_exists(at, "parts")) {
    GroupHandle parts = open_group(at, "parts");
    const Location pat{parts.get(), impl_->h5_path, at.child("parts")};
    for (const std::string& link : child_names(pat)) {
      GroupHandle pg = open_group(pat, link);
      const Location gat{pg.get(), impl_->h5_path, pat.child(link)};
      PartStateData p;
      p.link = link;
      std::size_t ne = 0;
      if (link_exists(gat, "eps_p")) p.eps_p = read_doubles(gat, "eps_p", 0, &ne);
      if (link_exists(gat, "von_mises")) p.von_mises_Pa = read_doubles(gat, "von_mises", 0, &ne);
      if (link_exists(gat, "stress")) p.stress_Pa = read_doubles(gat, "stress", 6, &ne);
      s.parts.push_back(std::move(p));
    }
  }
  return s;
}

TimingData ResultReader::timing() const {
  TimingData t;
  const Location root = impl_->root();
  if (!link_exists(root, "timing")) return t;
  GroupHandle g = open_group(root, "timing");
  const Location at{g.get(), impl_->h5_path, "/timing"};
  t.present = true;
  t.wall_seconds = read_number_attribute<double>(at, "wall_seconds", H5T_NATIVE_DOUBLE).value_or(0);
  t.coordinator_cpu_seconds =
      read_number_attribute<double>(at, "coordinator_cpu_seconds", H5T_NATIVE_DOUBLE).value_or(0);
  for (const std::string& link : child_names(at)) {
    GroupHandle dg = open_group(at, link);
    const Location dat{dg.get(), impl_->h5_path, at.child(link)};
    // absent attributes (files from before them): 0, threads 1
    const auto f64 = [&](const char* name) {
      return read_number_attribute<double>(dat, name, H5T_NATIVE_DOUBLE).value_or(0);
    };
    const auto i64 = [&](const char* name, std::int64_t absent = 0) {
      return read_number_attribute<std::int64_t>(dat, name, H5T_NATIVE_INT64).value_or(absent);
    };
    DomainTiming d;
    d.name = read_string_attribute(dat, "name").value_or(link);
    d.cpu_seconds = f64("cpu_seconds");
    d.cycles = i64("cycles");
    d.dt_min_s = f64("dt_min");
    d.elements = i64("elements");
    d.threads = i64("threads", 1);
    d.contact_seconds = f64("contact_seconds");
    d.contact_node_cycles = i64("contact_node_cycles");
    d.peak_rss_bytes = i64("peak_rss_bytes");
    d.setup_cpu_seconds = f64("setup_cpu_seconds");
    d.kernel_sampled_cycles = i64("kernel_sampled_cycles");
    d.hex_kernel_seconds = f64("hex_kernel_seconds");
    d.hex_element_cycles = i64("hex_element_cycles");
    d.shell_kernel_seconds = f64("shell_kernel_seconds");
    d.shell_element_cycles = i64("shell_element_cycles");
    d.global_step_seconds = f64("global_step_seconds");
    t.domains.push_back(std::move(d));
  }
  return t;
}

std::vector<ProbeSample> probe_samples(const ProbeHistory& h, std::size_t k) {
  std::vector<ProbeSample> rows(k);
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      rows[r].displacement_m[c] = h.displacement_m[3 * r + c];
      rows[r].velocity_m_s[c] = h.velocity_m_s[3 * r + c];
      rows[r].acceleration_m_s2[c] = h.acceleration_m_s2[3 * r + c];
    }
  }
  return rows;
}

std::vector<ContactSample> contact_samples(const ContactHistory& h, std::size_t k) {
  std::vector<ContactSample> rows(k);
  const bool energy = h.energy_J.size() >= k;
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t c = 0; c < 3; ++c) rows[r].force_N[c] = h.force_N[3 * r + c];
    rows[r].energy_J = energy ? h.energy_J[r] : std::numeric_limits<double>::quiet_NaN();
  }
  return rows;
}

}  // namespace crashlink::io
