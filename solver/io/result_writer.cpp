#include "solver/io/result_writer.h"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <set>

#include "solver/io/disk_space.h"
#include "solver/io/hdf5_handles.h"
#include "solver/io/xdmf_writer.h"

namespace crashlink::io {

std::string result_link_name(const std::string& name, const char* fallback, std::size_t index) {
  if (name.empty() || name == "." || name == "..") return fmt::format("{}_{}", fallback, index);
  std::string s = name;
  for (char& c : s) {
    if (c == '/') c = '_';
  }
  return s;
}

namespace {

using Clock = std::chrono::steady_clock;

/// The /history/glstat columns (docs/design.md §4) in GlstatSample order, with their units.
struct GlstatColumn {
  const char* name;
  const char* units;
  double GlstatSample::*value;
};
constexpr std::array<GlstatColumn, 11> kGlstat{{
    {"time", "s", &GlstatSample::time_s},
    {"kinetic_energy", "J", &GlstatSample::kinetic_energy_J},
    {"internal_energy", "J", &GlstatSample::internal_energy_J},
    {"hourglass_energy", "J", &GlstatSample::hourglass_energy_J},
    {"contact_energy", "J", &GlstatSample::contact_energy_J},
    {"external_work", "J", &GlstatSample::external_work_J},
    {"total_energy", "J", &GlstatSample::total_energy_J},
    {"energy_balance_error", "1", &GlstatSample::energy_balance_error},
    {"coupling_work", "J", &GlstatSample::coupling_work_J},
    {"scheme_energy", "J", &GlstatSample::scheme_energy_J},
    {"scheme_energy_time", "s", &GlstatSample::scheme_energy_time_s},
}};

/// Link names for a list of user names; throws ModelError on a collision.
template <class T, class NameOf>
std::vector<std::string> link_names(const std::vector<T>& items, NameOf name_of, const char* what) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < items.size(); ++i) {
    out.push_back(result_link_name(name_of(items[i]), what, i));
    if (!seen.insert(out.back()).second) {
      throw ModelError(fmt::format(
          "result writer: two {}s are named '{}' (after replacing '/' by '_'); give every {} a "
          "unique name in the scenario",
          what, out.back(), what));
    }
  }
  return out;
}

/// Checks the arrays the writer reads (sizes and index ranges); throws ModelError.
void check_model(const model::Model& m) {
  const std::size_t n = m.nodes.count();
  if (m.nodes.x0.size() != 3 * n) {
    throw ModelError(
        fmt::format("result writer: model '{}' has {} node ids but {} coordinates "
                    "(expected 3 per node)",
                    m.name, n, m.nodes.x0.size()));
  }
  for (const model::Part& p : m.parts) {
    const auto k = static_cast<std::size_t>(model::nodes_per_element(p.kind));
    if (p.connectivity.size() % k != 0) {
      throw ModelError(
          fmt::format("result writer: part '{}' has {} connectivity entries, not a "
                      "multiple of {} nodes per element",
                      p.name, p.connectivity.size(), k));
    }
    for (const std::int32_t node : p.connectivity) {
      if (node < 0 || static_cast<std::size_t>(node) >= n) {
        throw ModelError(
            fmt::format("result writer: part '{}' refers to node index {}, outside "
                        "[0, {})",
                        p.name, node, n));
      }
    }
  }
}

struct ProbeOut {
  std::string path;  // /history/probes/<name>
  DatasetHandle time, displacement, velocity, acceleration;
  std::vector<double> t, u, v, a;  // buffered rows: [k], [3k], [3k], [3k]
};

struct ContactOut {
  std::string path;              // /history/contacts/<name> or /history/rigid_walls/<name>
  std::string third = "energy";  // the third dataset: a contact's energy, a wall's work
  DatasetHandle time, force, energy;
  std::vector<double> t, f, e;  // buffered rows: [k], [3k], [k]
};

}  // namespace

struct ResultWriter::Impl {
  std::string h5_path;
  ResultWriterOptions options;
  FileHandle file;
  std::array<DatasetHandle, kGlstat.size()> glstat;
  std::array<std::vector<double>, kGlstat.size()> glstat_buffer;
  std::vector<ProbeOut> probes;
  std::vector<ContactOut> contacts;
  std::vector<ContactOut> walls;
  std::size_t buffered = 0;
  Clock::time_point last_flush = Clock::now();
  std::size_t node_count = 0;
  std::vector<double> x0;               // [3n] reference coordinates (the model may not outlive us)
  std::vector<std::string> part_links;  // link names of the parts
  std::vector<std::size_t> part_elements;
  XdmfDocument xdmf;

  Location root() const { return Location{file.get(), h5_path, "/"}; }

  void flush_file() {
    if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) {
      throw ResultFileError(h5_path, "/", "H5Fflush (flush the result file to disk)");
    }
  }

  /// Appends the buffered rows; the buffers are emptied even if a write fails (no row is ever
  /// written twice), but kept when the room check refuses the write (io::ensure_space; not when
  /// `closing`: the close writes in the reserve kept for it). Returns the number of rows written.
  std::size_t write_history(bool closing = false) {
    const std::size_t rows = buffered;
    if (rows > 0 && !closing) {
      // Before the buffers are handed to the Clear below: a disk too full keeps them for the
      // close, which writes them in the reserve.
      std::uint64_t need = 0;
      for (const auto& b : glstat_buffer) need += b.size();
      for (const ProbeOut& p : probes) need += p.t.size() + p.u.size() + p.v.size() + p.a.size();
      for (const ContactOut& c : contacts) need += c.t.size() + c.f.size() + c.e.size();
      for (const ContactOut& c : walls) need += c.t.size() + c.f.size() + c.e.size();
      ensure_space(h5_path, "/history", 8 * need);
    }
    struct Clear {
      Impl* self;
      ~Clear() {
        for (auto& b : self->glstat_buffer) b.clear();
        for (auto& p : self->probes) {
          p.t.clear();
          p.u.clear();
          p.v.clear();
          p.a.clear();
        }
        for (auto* list : {&self->contacts, &self->walls})
          for (auto& c : *list) {
            c.t.clear();
            c.f.clear();
            c.e.clear();
          }
        self->buffered = 0;
        self->last_flush = Clock::now();
      }
    } clear{this};
    if (rows == 0) return 0;
    for (std::size_t c = 0; c < kGlstat.size(); ++c) {
      append_rows(
          Location{glstat[c].get(), h5_path, std::string("/history/glstat/") + kGlstat[c].name},
          glstat_buffer[c], 0);
    }
    for (ProbeOut& p : probes) {
      append_rows(Location{p.time.get(), h5_path, p.path + "/time"}, p.t, 0);
      append_rows(Location{p.displacement.get(), h5_path, p.path + "/displacement"}, p.u, 3);
      append_rows(Location{p.velocity.get(), h5_path, p.path + "/velocity"}, p.v, 3);
      append_rows(Location{p.acceleration.get(), h5_path, p.path + "/acceleration"}, p.a, 3);
    }
    for (ContactOut& c : contacts) append_contact_out(c);
    for (ContactOut& c : walls) append_contact_out(c);
    return rows;
  }

  /// Appends the rows of `c` (buffered or given) to its three datasets.
  void append_contact_out(ContactOut& c) { append_contact_rows_to(c, c.t, c.f, c.e); }
  void append_contact_rows_to(ContactOut& c, std::span<const double> t, std::span<const double> f,
                              std::span<const double> e) {
    append_rows(Location{c.time.get(), h5_path, c.path + "/time"}, t, 0);
    append_rows(Location{c.force.get(), h5_path, c.path + "/force"}, f, 3);
    append_rows(Location{c.energy.get(), h5_path, c.path + "/" + c.third}, e, 0);
  }

  void write_mesh(const model::Model& m) {
    GroupHandle mesh = create_group(root(), "mesh");
    const Location at{mesh.get(), h5_path, "/mesh"};
    const hsize_t n = node_count;
    const hsize_t xdims[2] = {n, 3};
    write_dataset(at, "coordinates", std::span<const double>(m.nodes.x0), xdims, "m");
    const hsize_t ndims[1] = {n};
    write_dataset(at, "node_ids", std::span<const std::int64_t>(m.nodes.id), ndims);
    std::vector<std::string> names;
    for (const auto& p : m.parts) names.push_back(p.name);
    write_strings(at, "part_names", names);

    GroupHandle parts = create_group(at, "parts");
    const Location pat{parts.get(), h5_path, "/mesh/parts"};
    xdmf.node_count = node_count;
    xdmf.reference_coordinates = "/mesh/coordinates";
    for (std::size_t i = 0; i < m.parts.size(); ++i) {
      const model::Part& p = m.parts[i];
      const auto k = static_cast<hsize_t>(model::nodes_per_element(p.kind));
      const hsize_t ne = p.connectivity.size() / k;
      GroupHandle g = create_group(pat, part_links[i]);
      const Location gat{g.get(), h5_path, pat.child(part_links[i])};
      write_attribute(gat, "name", p.name);
      write_attribute(gat, "kind",
                      std::string(p.kind == model::ElementKind::Hex8 ? "hex8" : "shell4"));
      write_attribute(gat, "index", static_cast<std::int64_t>(i));
      if (p.user_id != 0) write_attribute(gat, "id", p.user_id);  // a deck's *PART PID
      const hsize_t cdims[2] = {ne, k};
      write_dataset(gat, "connectivity", std::span<const std::int32_t>(p.connectivity), cdims);
      const hsize_t edims[1] = {ne};
      if (p.element_id.size() == ne) {
        write_dataset(gat, "element_ids", std::span<const std::int64_t>(p.element_id), edims);
      } else {  // ids not given: 1-based positions, so the dataset always exists
        std::vector<std::int64_t> ids(ne);
        for (std::size_t e = 0; e < ne; ++e) ids[e] = static_cast<std::int64_t>(e + 1);
        write_dataset(gat, "element_ids", std::span<const std::int64_t>(ids), edims);
      }
      part_elements.push_back(ne);
      // ParaView lists the grids by name: a deck's part shows its PID too
      xdmf.parts.push_back(
          XdmfPart{p.user_id != 0 ? fmt::format("{} (PID {})", p.name, p.user_id) : p.name,
                   p.kind == model::ElementKind::Hex8, ne, gat.path + "/connectivity"});
    }
  }

  void create_history(const model::Model& m, const std::vector<std::string>& probe_links) {
    const hsize_t chunk = options.history_chunk_rows == 0 ? 1024 : options.history_chunk_rows;
    GroupHandle history = create_group(root(), "history");
    const Location hat{history.get(), h5_path, "/history"};
    GroupHandle gl = create_group(hat, "glstat");
    const Location gat{gl.get(), h5_path, "/history/glstat"};
    for (std::size_t c = 0; c < kGlstat.size(); ++c) {
      glstat[c] = create_extendible(gat, kGlstat[c].name, 0, chunk, kGlstat[c].units);
    }
    GroupHandle pr = create_group(hat, "probes");
    const Location pat{pr.get(), h5_path, "/history/probes"};
    for (std::size_t i = 0; i < m.probes.size(); ++i) {
      const model::Probe& probe = m.probes[i];
      GroupHandle g = create_group(pat, probe_links[i]);
      ProbeOut out;
      out.path = pat.child(probe_links[i]);
      const Location at{g.get(), h5_path, out.path};
      write_attribute(at, "name", probe.name);
      if (probe.kind == model::Probe::Kind::Node) {
        write_attribute(at, "kind", std::string("node"));
        const bool known = probe.index >= 0 && static_cast<std::size_t>(probe.index) < node_count;
        write_attribute(
            at, "node_id",
            known ? m.nodes.id[static_cast<std::size_t>(probe.index)] : std::int64_t{-1});
      } else {
        write_attribute(at, "kind", std::string("rigid_body"));
        const bool known =
            probe.index >= 0 && static_cast<std::size_t>(probe.index) < m.rigid_bodies.size();
        write_attribute(
            at, "rigid_body",
            known ? m.rigid_bodies[static_cast<std::size_t>(probe.index)].name : std::string());
      }
      out.time = create_extendible(at, "time", 0, chunk, "s");
      out.displacement = create_extendible(at, "displacement", 3, chunk, "m");
      out.velocity = create_extendible(at, "velocity", 3, chunk, "m/s");
      out.acceleration = create_extendible(at, "acceleration", 3, chunk, "m/s^2");
      probes.push_back(std::move(out));
    }
    GroupHandle co = create_group(hat, "contacts");
    const Location cat{co.get(), h5_path, "/history/contacts"};
    const std::vector<std::string> contact_links = link_names(
        m.contacts, [](const model::Contact& c) { return c.name; }, "contact");
    for (std::size_t i = 0; i < m.contacts.size(); ++i) {
      GroupHandle g = create_group(cat, contact_links[i]);
      ContactOut out;
      out.path = cat.child(contact_links[i]);
      const Location at{g.get(), h5_path, out.path};
      write_attribute(at, "name", m.contacts[i].name);
      out.time = create_extendible(at, "time", 0, chunk, "s");
      out.force = create_extendible(at, "force", 3, chunk, "N");
      out.energy = create_extendible(at, "energy", 0, chunk, "J");
      contacts.push_back(std::move(out));
    }
    if (m.rigid_walls.empty()) return;  // files without walls keep their old layout
    GroupHandle wo = create_group(hat, "rigid_walls");
    const Location wat{wo.get(), h5_path, "/history/rigid_walls"};
    const std::vector<std::string> wall_links = link_names(
        m.rigid_walls, [](const model::RigidWall& w) { return w.name; }, "rigid wall");
    for (std::size_t i = 0; i < m.rigid_walls.size(); ++i) {
      GroupHandle g = create_group(wat, wall_links[i]);
      ContactOut out;
      out.path = wat.child(wall_links[i]);
      out.third = "work";
      const Location at{g.get(), h5_path, out.path};
      write_attribute(at, "name", m.rigid_walls[i].name);
      out.time = create_extendible(at, "time", 0, chunk, "s");
      out.force = create_extendible(at, "force", 3, chunk, "N");
      out.energy = create_extendible(at, "work", 0, chunk, "J");
      walls.push_back(std::move(out));
    }
  }
};

ResultWriter::ResultWriter(const std::string& dir, const model::Model& model,
                           ResultWriterOptions options) {
  check_model(model);
  const std::vector<std::string> part_links = link_names(
      model.parts, [](const model::Part& p) { return p.name; }, "part");
  const std::vector<std::string> probe_links = link_names(
      model.probes, [](const model::Probe& p) { return p.name; }, "probe");

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw ResultFileError(dir, "/",
                          fmt::format("cannot create the output directory: {}", ec.message()));
  }
  const std::string stem = options.file_stem.empty() ? std::string("result") : options.file_stem;
  h5_path_ = (std::filesystem::path(dir) / (stem + ".h5")).string();
  xdmf_path_ = (std::filesystem::path(dir) / (stem + ".xdmf")).string();

  auto impl = std::make_unique<Impl>();
  impl->h5_path = h5_path_;
  impl->options = options;
  impl->node_count = model.nodes.count();
  impl->x0 = model.nodes.x0;
  impl->part_links = part_links;
  impl->xdmf.h5_file = stem + ".h5";
  impl->file = create_file(h5_path_);
  const Location root = impl->root();
  write_attribute(root, "format", std::string("crashlink-result"));
  write_attribute(root, "format_version", std::int64_t{1});
  write_attribute(root, "model", model.name);
  impl->write_mesh(model);
  impl->create_history(model, probe_links);
  {
    GroupHandle states = create_group(root, "states");
    write_attribute(Location{states.get(), h5_path_, "/states"}, "count", std::int64_t{0});
  }
  impl->flush_file();
  write_xdmf(xdmf_path_, impl->xdmf);
  impl_ = std::move(impl);
}

ResultWriter::~ResultWriter() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crashlink: closing the result file failed: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "crashlink: closing the result file %s failed\n", h5_path_.c_str());
  }
}

namespace {
[[noreturn]] void closed(const std::string& path, const char* call) {
  throw ResultFileError(path, "/",
                        fmt::format("{} after close(): the result writer is closed; "
                                    "write everything before closing it",
                                    call));
}
}  // namespace

void ResultWriter::append_history(const GlstatSample& g, const std::vector<ProbeSample>& probes,
                                  const std::vector<ContactSample>& contacts,
                                  const std::vector<ContactSample>& walls) {
  if (!impl_) closed(h5_path_, "append_history");
  Impl& w = *impl_;
  if (contacts.size() != w.contacts.size()) {
    throw ResultFileError(h5_path_, "/history/contacts",
                          fmt::format("append_history: {} contact samples given, the model has {} "
                                      "contacts (pass one sample per model.contacts, same order)",
                                      contacts.size(), w.contacts.size()));
  }
  if (walls.size() != w.walls.size()) {
    throw ResultFileError(h5_path_, "/history/rigid_walls",
                          fmt::format("append_history: {} wall samples given, the model has {} "
                                      "rigid walls (pass one sample per model.rigid_walls, same "
                                      "order)",
                                      walls.size(), w.walls.size()));
  }
  auto buffer = [&](ContactOut& c, const ContactSample& x) {
    c.t.push_back(g.time_s);
    c.f.insert(c.f.end(), x.force_N, x.force_N + 3);
    c.e.push_back(x.energy_J);
  };
  for (std::size_t i = 0; i < contacts.size(); ++i) buffer(w.contacts[i], contacts[i]);
  for (std::size_t i = 0; i < walls.size(); ++i) buffer(w.walls[i], walls[i]);
  if (probes.size() != w.probes.size()) {
    throw ResultFileError(h5_path_, "/history/probes",
                          fmt::format("append_history: {} probe samples given, the model has {} "
                                      "probes (pass one sample per model.probes, same order)",
                                      probes.size(), w.probes.size()));
  }
  for (std::size_t c = 0; c < kGlstat.size(); ++c)
    w.glstat_buffer[c].push_back(g.*kGlstat[c].value);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    ProbeOut& p = w.probes[i];
    p.t.push_back(g.time_s);
    p.u.insert(p.u.end(), probes[i].displacement_m, probes[i].displacement_m + 3);
    p.v.insert(p.v.end(), probes[i].velocity_m_s, probes[i].velocity_m_s + 3);
    p.a.insert(p.a.end(), probes[i].acceleration_m_s2, probes[i].acceleration_m_s2 + 3);
  }
  ++w.buffered;
  const auto wall = std::chrono::duration<double>(Clock::now() - w.last_flush).count();
  if (w.buffered >= w.options.history_flush_samples || wall >= w.options.history_flush_wall_s) {
    flush_history();
  }
}

void ResultWriter::flush_history() {
  if (!impl_) closed(h5_path_, "flush_history");
  history_rows_ += impl_->write_history();
  impl_->flush_file();
}

void ResultWriter::flush() {
  flush_history();
}

void ResultWriter::append_glstat_rows(std::span<const GlstatSample> rows) {
  flush_history();
  Impl& w = *impl_;
  std::vector<double> column(rows.size());
  for (std::size_t c = 0; c < kGlstat.size(); ++c) {
    for (std::size_t i = 0; i < rows.size(); ++i) column[i] = rows[i].*kGlstat[c].value;
    append_rows(
        Location{w.glstat[c].get(), h5_path_, std::string("/history/glstat/") + kGlstat[c].name},
        column, 0);
  }
  history_rows_ += rows.size();
  w.flush_file();
}

void ResultWriter::append_probe_rows(std::size_t probe, std::span<const double> time_s,
                                     std::span<const ProbeSample> rows) {
  flush_history();
  Impl& w = *impl_;
  if (probe >= w.probes.size() || time_s.size() != rows.size()) {
    throw ResultFileError(h5_path_, "/history/probes",
                          fmt::format("append_probe_rows: probe {} of {} with {} times and {} rows "
                                      "(internal error: one time per row, a model probe index)",
                                      probe, w.probes.size(), time_s.size(), rows.size()));
  }
  ProbeOut& p = w.probes[probe];
  std::vector<double> u, v, a;
  for (const ProbeSample& r : rows) {
    u.insert(u.end(), r.displacement_m, r.displacement_m + 3);
    v.insert(v.end(), r.velocity_m_s, r.velocity_m_s + 3);
    a.insert(a.end(), r.acceleration_m_s2, r.acceleration_m_s2 + 3);
  }
  append_rows(Location{p.time.get(), h5_path_, p.path + "/time"}, time_s, 0);
  append_rows(Location{p.displacement.get(), h5_path_, p.path + "/displacement"}, u, 3);
  append_rows(Location{p.velocity.get(), h5_path_, p.path + "/velocity"}, v, 3);
  append_rows(Location{p.acceleration.get(), h5_path_, p.path + "/acceleration"}, a, 3);
  w.flush_file();
}

void ResultWriter::append_contact_rows(std::size_t contact, std::span<const double> time_s,
                                       std::span<const ContactSample> rows) {
  append_item_rows(false, contact, time_s, rows);
}

void ResultWriter::append_wall_rows(std::size_t wall, std::span<const double> time_s,
                                    std::span<const ContactSample> rows) {
  append_item_rows(true, wall, time_s, rows);
}

void ResultWriter::append_item_rows(bool wall, std::size_t item, std::span<const double> time_s,
                                    std::span<const ContactSample> rows) {
  flush_history();
  Impl& w = *impl_;
  auto& list = wall ? w.walls : w.contacts;
  if (item >= list.size() || time_s.size() != rows.size()) {
    throw ResultFileError(
        h5_path_, wall ? "/history/rigid_walls" : "/history/contacts",
        fmt::format("append_{}_rows: {} {} of {} with {} times and {} rows (internal error: one "
                    "time per row, a model {} index)",
                    wall ? "wall" : "contact", wall ? "wall" : "contact", item, list.size(),
                    time_s.size(), rows.size(), wall ? "rigid wall" : "contact"));
  }
  ContactOut& c = list[item];
  std::vector<double> f, e;
  for (const ContactSample& r : rows) {
    f.insert(f.end(), r.force_N, r.force_N + 3);
    e.push_back(r.energy_J);
  }
  w.append_contact_rows_to(c, time_s, f, e);
  w.flush_file();
}

void ResultWriter::write_field_state(const FieldState& s) {
  if (!impl_) closed(h5_path_, "write_field_state");
  Impl& w = *impl_;
  const std::size_t k = state_count_;
  const std::string path = fmt::format("/states/{}", k);
  const std::size_t n = w.node_count;
  auto check_size = [&](std::span<const double> a, std::size_t expected, const std::string& what,
                        bool required) {
    if ((required || !a.empty()) && a.size() != expected) {
      throw ResultFileError(h5_path_, path + "/" + what,
                            fmt::format("write_field_state: {} has {} values, expected {}", what,
                                        a.size(), expected));
    }
  };
  check_size(s.displacement_m, 3 * n, "displacement", true);
  check_size(s.velocity_m_s, 3 * n, "velocity", false);
  if (!s.parts.empty() && s.parts.size() != w.part_links.size()) {
    throw ResultFileError(h5_path_, path,
                          fmt::format("write_field_state: {} part states given, the model has {} "
                                      "parts (pass none or one per model.parts, same order)",
                                      s.parts.size(), w.part_links.size()));
  }
  for (std::size_t p = 0; p < s.parts.size(); ++p) {
    const std::size_t ne = w.part_elements[p];
    const std::string part = "parts/" + w.part_links[p];
    check_size(s.parts[p].eps_p, ne, part + "/eps_p", false);
    check_size(s.parts[p].von_mises_Pa, ne, part + "/von_mises", false);
    check_size(s.parts[p].stress_Pa, 6 * ne, part + "/stress", false);
  }

  std::uint64_t values = s.displacement_m.size() + s.velocity_m_s.size();
  for (const auto& ps : s.parts)
    values += ps.eps_p.size() + ps.von_mises_Pa.size() + ps.stress_Pa.size();
  ensure_space(h5_path_, path, 8 * values);

  GroupHandle states = open_group(w.root(), "states");
  const Location sat{states.get(), h5_path_, "/states"};
  GroupHandle g = create_group(sat, std::to_string(k));
  const Location at{g.get(), h5_path_, path};
  write_attribute(at, "time", s.time_s);
  XdmfState xs;
  xs.time_s = s.time_s;
  const hsize_t ndims[2] = {n, 3};
  std::vector<double> x(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) x[i] = w.x0[i] + s.displacement_m[i];
  write_dataset(at, "coordinates", std::span<const double>(x), ndims, "m");
  write_dataset(at, "displacement", s.displacement_m, ndims, "m");
  xs.coordinates = path + "/coordinates";
  xs.displacement = path + "/displacement";
  if (!s.velocity_m_s.empty()) {
    write_dataset(at, "velocity", s.velocity_m_s, ndims, "m/s");
    xs.velocity = path + "/velocity";
  }
  if (!s.parts.empty()) {
    GroupHandle parts = create_group(at, "parts");
    const Location pat{parts.get(), h5_path_, path + "/parts"};
    for (std::size_t p = 0; p < s.parts.size(); ++p) {
      const PartFieldState& f = s.parts[p];
      XdmfPartFields xf;
      if (!f.eps_p.empty() || !f.von_mises_Pa.empty() || !f.stress_Pa.empty()) {
        GroupHandle pg = create_group(pat, w.part_links[p]);
        const Location gat{pg.get(), h5_path_, pat.child(w.part_links[p])};
        const hsize_t ne = w.part_elements[p];
        const hsize_t edims[1] = {ne};
        if (!f.eps_p.empty()) {
          write_dataset(gat, "eps_p", f.eps_p, edims, "1");
          xf.eps_p = gat.path + "/eps_p";
        }
        if (!f.von_mises_Pa.empty()) {
          write_dataset(gat, "von_mises", f.von_mises_Pa, edims, "Pa");
          xf.von_mises = gat.path + "/von_mises";
        }
        if (!f.stress_Pa.empty()) {
          const hsize_t sdims[2] = {ne, 6};
          write_dataset(gat, "stress", f.stress_Pa, sdims, "Pa");
          DatasetHandle ds(H5Dopen2(pg.get(), "stress", H5P_DEFAULT));
          if (!ds) throw ResultFileError(h5_path_, gat.path + "/stress", "H5Dopen2");
          write_attribute(Location{ds.get(), h5_path_, gat.path + "/stress"}, "components",
                          std::string("xx yy zz xy yz zx"));
          xf.stress = gat.path + "/stress";
        }
      }
      xs.parts.push_back(std::move(xf));
    }
  }
  write_attribute(sat, "count", static_cast<std::int64_t>(k + 1));
  ++state_count_;
  w.xdmf.states.push_back(std::move(xs));
  w.flush_file();
  write_xdmf(xdmf_path_, w.xdmf);
}

void ResultWriter::write_timing(double wall_seconds, double coordinator_cpu_seconds,
                                const std::vector<DomainTiming>& domains) {
  if (!impl_) closed(h5_path_, "write_timing");
  Impl& w = *impl_;
  const std::vector<std::string> links = link_names(
      domains, [](const DomainTiming& d) { return d.name; }, "domain");
  const Location root = w.root();
  GroupHandle timing =
      link_exists(root, "timing") ? open_group(root, "timing") : create_group(root, "timing");
  const Location at{timing.get(), h5_path_, "/timing"};
  write_attribute(at, "wall_seconds", wall_seconds);
  write_attribute(at, "coordinator_cpu_seconds", coordinator_cpu_seconds);
  for (std::size_t i = 0; i < domains.size(); ++i) {
    const DomainTiming& d = domains[i];
    GroupHandle g =
        link_exists(at, links[i]) ? open_group(at, links[i]) : create_group(at, links[i]);
    const Location dat{g.get(), h5_path_, at.child(links[i])};
    write_attribute(dat, "name", d.name);
    write_attribute(dat, "cpu_seconds", d.cpu_seconds);
    write_attribute(dat, "cycles", d.cycles);
    write_attribute(dat, "dt_min", d.dt_min_s);
    write_attribute(dat, "elements", d.elements);
    write_attribute(dat, "threads", d.threads);
    write_attribute(dat, "contact_seconds", d.contact_seconds);
    write_attribute(dat, "contact_node_cycles", d.contact_node_cycles);
    write_attribute(dat, "peak_rss_bytes", d.peak_rss_bytes);
    write_attribute(dat, "setup_cpu_seconds", d.setup_cpu_seconds);
    write_attribute(dat, "kernel_sampled_cycles", d.kernel_sampled_cycles);
    write_attribute(dat, "hex_kernel_seconds", d.hex_kernel_seconds);
    write_attribute(dat, "hex_element_cycles", d.hex_element_cycles);
    write_attribute(dat, "shell_kernel_seconds", d.shell_kernel_seconds);
    write_attribute(dat, "shell_element_cycles", d.shell_element_cycles);
    write_attribute(dat, "global_step_seconds", d.global_step_seconds);
  }
  w.flush_file();
}

void ResultWriter::write_spot_weld_failures(const std::vector<SpotWeldFailure>& failures) {
  if (!impl_) closed(h5_path_, "write_spot_weld_failures");
  if (failures.empty()) return;
  Impl& w = *impl_;
  const Location root = w.root();
  GroupHandle events =
      link_exists(root, "events") ? open_group(root, "events") : create_group(root, "events");
  const Location eat{events.get(), h5_path_, "/events"};
  // written once, at the end: a file that has them already (a run's file resumed after its end)
  // gets them anew
  if (link_exists(eat, "spot_weld_failures") &&
      H5Ldelete(events.get(), "spot_weld_failures", H5P_DEFAULT) < 0)
    throw ResultFileError(h5_path_, "/events/spot_weld_failures", "H5Ldelete (replace the list)");
  GroupHandle g = create_group(eat, "spot_weld_failures");
  const Location at{g.get(), h5_path_, "/events/spot_weld_failures"};
  write_attribute(at, "count", static_cast<std::int64_t>(failures.size()));
  for (std::size_t k = 0; k < failures.size(); ++k) {
    const std::string link = std::to_string(k);
    GroupHandle fg = create_group(at, link);
    const Location fat{fg.get(), h5_path_, at.child(link)};
    write_attribute(fat, "name", failures[k].name);
    write_attribute(fat, "time", failures[k].time_s);
    write_attribute(fat, "tension", failures[k].tension_N);
    write_attribute(fat, "shear", failures[k].shear_N);
  }
  w.flush_file();
}

void ResultWriter::close() {
  if (!impl_) return;
  std::unique_ptr<Impl> w = std::move(impl_);  // closed from here on, whatever happens below
  std::exception_ptr first;
  auto attempt = [&](auto&& step) {
    try {
      step();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  };
  attempt([&] { history_rows_ += w->write_history(true); });
  attempt([&] {
    for (auto& d : w->glstat) d.reset();
    w->probes.clear();
    w->contacts.clear();
    if (!w->file.close()) throw ResultFileError(h5_path_, "/", "H5Fclose (close the result file)");
  });
  attempt([&] { write_xdmf(xdmf_path_, w->xdmf); });
  if (first) std::rethrow_exception(first);
}

}  // namespace crashlink::io
