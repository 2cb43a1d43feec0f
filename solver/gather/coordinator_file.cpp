// DIR/coordinator.h5 in the gather (coordinator_file.h).
#include "solver/gather/coordinator_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <vector>

#include "core/errors.h"
#include "solver/io/hdf5_handles.h"

namespace crashlink::gather {

namespace fs = std::filesystem;

namespace {

std::optional<double> double_attribute(const io::Location& at, const char* name) {
  const htri_t exists = H5Aexists(at.id, name);
  if (exists < 0) throw io::ResultFileError(at.file, at.path + "@" + name, "H5Aexists");
  if (exists == 0) return std::nullopt;
  io::AttributeHandle a(H5Aopen(at.id, name, H5P_DEFAULT));
  double v = 0.0;
  if (!a || H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    throw io::ResultFileError(at.file, at.path + "@" + name, "H5Aread");
  return v;
}

/// The names of the groups directly under `at`, in name order.
std::vector<std::string> child_groups(const io::Location& at) {
  H5G_info_t info;
  if (H5Gget_info(at.id, &info) < 0) throw io::ResultFileError(at.file, at.path, "H5Gget_info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(at.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw io::ResultFileError(at.file, at.path, "H5Lget_name_by_idx");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    if (H5Lget_name_by_idx(at.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                           H5P_DEFAULT) < 0)
      throw io::ResultFileError(at.file, at.path, "H5Lget_name_by_idx");
    name.resize(static_cast<std::size_t>(len));
    io::GroupHandle g(H5Gopen2(at.id, name.c_str(), H5P_DEFAULT));  // a group, not a dataset?
    if (g) {
      names.push_back(std::move(name));
    } else {
      H5Eclear2(H5E_DEFAULT);
    }
  }
  return names;
}

std::string coordinator_path(const std::string& dir) {
  return (fs::path(dir) / "coordinator.h5").string();
}

}  // namespace

CoordinatorTiming read_coordinator_timing(const std::string& dir, GatherReport& report) {
  CoordinatorTiming t;
  const std::string path = coordinator_path(dir);
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    report.notes.push_back(
        "coordinator.h5 absent: no /coupling histories; /timing wall_seconds and "
        "coordinator_cpu_seconds written as 0");
    return t;
  }
  try {
    io::FileHandle file = io::open_file_read(path);
    const io::Location root{file.get(), path, "/"};
    if (io::link_exists(root, "timing")) {
      io::GroupHandle g = io::open_group(root, "timing");
      const io::Location at{g.get(), path, "/timing"};
      t.wall_seconds = double_attribute(at, "wall_seconds").value_or(0.0);
      t.coordinator_cpu_seconds = double_attribute(at, "coordinator_cpu_seconds").value_or(0.0);
      for (const std::string& link : child_groups(at)) {
        io::GroupHandle dg = io::open_group(at, link);
        const auto w =
            double_attribute(io::Location{dg.get(), path, at.child(link)}, "wait_seconds");
        if (w) t.wait_seconds[link] = *w;
      }
    } else {
      report.notes.push_back(
          "coordinator.h5 has no /timing (the coordinator did not finish): wall_seconds and "
          "coordinator_cpu_seconds written as 0");
    }
    t.present = true;
  } catch (const Error& e) {
    report.notes.push_back(fmt::format("coordinator.h5 unreadable, not used: {}", e.what()));
    t = CoordinatorTiming{};
  }
  return t;
}

void finish_result_file(const std::string& result_h5, const std::string& dir,
                        const CoordinatorTiming& timing,
                        const std::map<std::string, std::string>& names, GatherReport& report) {
  io::quiet_hdf5_errors();
  io::FileHandle out(H5Fopen(result_h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  if (!out) throw io::ResultFileError(result_h5, "/", "H5Fopen (reopen to add /coupling)");
  const io::Location root{out.get(), result_h5, "/"};
  if (timing.present) {
    const std::string path = coordinator_path(dir);
    try {
      io::FileHandle in = io::open_file_read(path);
      if (io::link_exists(io::Location{in.get(), path, "/"}, "coupling")) {
        if (H5Ocopy(in.get(), "coupling", out.get(), "coupling", H5P_DEFAULT, H5P_DEFAULT) < 0)
          throw io::ResultFileError(result_h5, "/coupling", "H5Ocopy (copy from coordinator.h5)");
      } else {
        report.notes.push_back("coordinator.h5 has no /coupling group: nothing copied");
      }
    } catch (const Error& e) {
      report.notes.push_back(fmt::format("/coupling not copied: {}", e.what()));
    }
    io::GroupHandle tg = io::link_exists(root, "timing") ? io::open_group(root, "timing")
                                                         : io::create_group(root, "timing");
    const io::Location tat{tg.get(), result_h5, "/timing"};
    for (const auto& [link, seconds] : timing.wait_seconds) {
      const bool exists = io::link_exists(tat, link);
      io::GroupHandle g = exists ? io::open_group(tat, link) : io::create_group(tat, link);
      const io::Location at{g.get(), result_h5, tat.child(link)};
      if (!exists) {
        const auto n = names.find(link);
        io::write_attribute(at, "name", n != names.end() ? n->second : link);
      }
      io::write_attribute(at, "wait_seconds", seconds);
    }
  }
  if (!report.notes.empty()) {
    std::string text;
    for (const std::string& n : report.notes) text += n + "\n";
    io::write_attribute(root, "gather_notes", text);
  }
  if (H5Fflush(out.get(), H5F_SCOPE_GLOBAL) < 0)
    throw io::ResultFileError(result_h5, "/", "H5Fflush");
  if (!out.close()) throw io::ResultFileError(result_h5, "/", "H5Fclose");
}

}  // namespace crashlink::gather
