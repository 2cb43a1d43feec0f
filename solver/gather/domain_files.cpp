// Opening the per-domain result files of a coupled run (domain_files.h).
#include "solver/gather/domain_files.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <unordered_map>

#include "core/errors.h"
#include "solver/io/hdf5_handles.h"

namespace crashlink::gather {

namespace fs = std::filesystem;

std::string domain_file_path(const std::string& dir, const std::string& name, std::size_t index) {
  const std::string link = io::result_link_name(name, "domain", index);
  const fs::path base = fs::path(dir) / "domains";
  const fs::path flat = base / (link + ".h5");
  std::error_code ec;
  if (fs::exists(flat, ec)) return flat.string();
  const fs::path nested = base / link / "result.h5";
  if (fs::exists(nested, ec)) return nested.string();
  return flat.string();
}

namespace {

/// User ids and names of the global model -> indices.
struct GlobalIndex {
  std::unordered_map<std::int64_t, std::int32_t> node;
  std::unordered_map<std::string, int> part;
  std::vector<std::unordered_map<std::int64_t, std::int32_t>> element;  // [parts]

  explicit GlobalIndex(const model::Model& g) {
    for (std::size_t i = 0; i < g.nodes.count(); ++i)
      node.emplace(g.nodes.id[i], static_cast<std::int32_t>(i));
    element.resize(g.parts.size());
    for (std::size_t p = 0; p < g.parts.size(); ++p) {
      part.emplace(g.parts[p].name, static_cast<int>(p));
      const auto& ids = g.parts[p].element_id;
      for (std::size_t e = 0; e < ids.size(); ++e)
        element[p].emplace(ids[e], static_cast<std::int32_t>(e));
    }
  }
};

/// Fills the row maps of `f` (its reader open); throws ModelError naming the file when an id or a
/// part does not belong to the global model or to the domain of the decomposition.
void map_rows(DomainFile& f, const model::Model& global, const partition::DomainModel& dm,
              const GlobalIndex& gi) {
  const std::vector<std::int64_t> ids = f.reader->node_ids();
  f.row_global.resize(ids.size());
  f.row_owned.resize(ids.size());
  for (std::size_t r = 0; r < ids.size(); ++r) {
    const auto it = gi.node.find(ids[r]);
    if (it == gi.node.end()) {
      throw ModelError(
          fmt::format("{}: node id {} is not a node of model '{}' (the file belongs "
                      "to another model)",
                      f.path, ids[r], global.name));
    }
    const auto l = std::lower_bound(dm.global_node.begin(), dm.global_node.end(), it->second);
    if (l == dm.global_node.end() || *l != it->second) {
      throw ModelError(
          fmt::format("{}: node id {} is not in domain '{}' of the decomposition "
                      "(the file was written for another decomposition or scheme)",
                      f.path, ids[r], dm.name));
    }
    const auto lu = static_cast<std::size_t>(l - dm.global_node.begin());
    f.row_global[r] = it->second;
    f.row_owned[r] = dm.ghost[lu] == 0 && dm.copy[lu] == 0 ? 1 : 0;
  }
  for (io::MeshPartInfo& mp : f.reader->mesh_parts()) {
    const auto p = gi.part.find(mp.name);
    if (p == gi.part.end()) {
      throw ModelError(
          fmt::format("{}: part '{}' is not a part of model '{}'", f.path, mp.name, global.name));
    }
    DomainFile::Part part;
    part.link = mp.link;
    part.global_part = p->second;
    const auto& emap = gi.element[static_cast<std::size_t>(p->second)];
    for (const std::int64_t id : mp.element_ids) {
      const auto e = emap.find(id);
      if (e == emap.end()) {
        throw ModelError(
            fmt::format("{}: element id {} is not an element of part '{}' of model "
                        "'{}'",
                        f.path, id, mp.name, global.name));
      }
      part.element.push_back(e->second);
    }
    f.parts.push_back(std::move(part));
  }
}

/// The file name relative to DIR for messages ("domains/<name>.h5").
std::string short_name(const std::string& dir, const std::string& path) {
  std::error_code ec;
  const fs::path rel = fs::relative(path, dir, ec);
  return ec || rel.empty() ? path : rel.string();
}

}  // namespace

std::vector<DomainFile> open_domain_files(const model::Model& global,
                                          const partition::Decomposition& dec,
                                          const std::string& dir, GatherReport& report) {
  const GlobalIndex gi(global);
  std::vector<DomainFile> files;
  std::vector<std::string> failures;
  bool all_model_errors = true;
  for (std::size_t d = 0; d < dec.domains.size(); ++d) {
    const partition::DomainModel& dm = dec.domains[d];
    if (dm.empty()) continue;
    DomainFile f;
    f.name = dm.name;
    f.domain = static_cast<int>(d);
    f.path = domain_file_path(dir, dm.name, d);
    const std::string shown = short_name(dir, f.path);
    auto give_up = [&](const std::string& why, bool model_error) {
      f.reader.reset();
      f.row_global.clear();
      f.row_owned.clear();
      f.parts.clear();
      report.missing.push_back(dm.name);
      report.notes.push_back(fmt::format("domain '{}': {} not used: {}", dm.name, shown, why));
      failures.push_back(fmt::format("{}: {}", f.path, why));
      all_model_errors = all_model_errors && model_error;
    };
    std::error_code ec;
    if (!fs::exists(f.path, ec)) {
      give_up("the file is absent (the daemon wrote nothing?)", false);
      files.push_back(std::move(f));
      continue;
    }
    try {
      f.reader.emplace(f.path);
      map_rows(f, global, dm, gi);
    } catch (const ModelError& e) {
      give_up(e.what(), true);
      files.push_back(std::move(f));
      continue;
    } catch (const Error& e) {
      give_up(e.what(), false);
      files.push_back(std::move(f));
      continue;
    }
    try {
      f.glstat = f.reader->glstat();
    } catch (const Error& e) {
      report.notes.push_back(fmt::format("domain '{}': {}: glstat unreadable, not summed: {}",
                                         dm.name, shown, e.what()));
    }
    try {
      const std::size_t count = f.reader->state_count();
      for (std::size_t k = 0; k < count; ++k) f.state_times.push_back(f.reader->state_time(k));
    } catch (const Error& e) {
      report.notes.push_back(
          fmt::format("domain '{}': {}: field states after the first {} "
                      "unreadable: {}",
                      dm.name, shown, f.state_times.size(), e.what()));
    }
    report.domains_read.push_back(dm.name);
    files.push_back(std::move(f));
  }
  if (report.domains_read.empty()) {
    const std::string what =
        failures.empty()
            ? std::string("the decomposition has no non-empty domain")
            : fmt::format("no domain result file could be used: {}", fmt::join(failures, "; "));
    if (all_model_errors && !failures.empty()) throw ModelError(fmt::format("gather: {}", what));
    throw io::ResultFileError((fs::path(dir) / "domains").string(), "/", what);
  }
  return files;
}

}  // namespace crashlink::gather
