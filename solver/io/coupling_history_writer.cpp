// The coordinator's interface histories, DIR/coordinator.h5 (coupling_history_writer.h).
#include "solver/io/coupling_history_writer.h"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <set>

#include "solver/io/hdf5_handles.h"
#include "solver/io/result_writer.h"  // result_link_name

namespace crashlink::io {

namespace {

using Clock = std::chrono::steady_clock;
constexpr hsize_t kChunkRows = 1024;

/// The [k] columns of an interface group, in CouplingSample order, with their units.
struct Column {
  const char* name;
  const char* units;
  double CouplingSample::*value;
};
constexpr std::array<Column, 5> kColumns{{
    {"time", "s", &CouplingSample::time_s},
    {"velocity_jump", "m/s", &CouplingSample::velocity_jump_m_s},
    {"displacement_gap", "m", &CouplingSample::displacement_gap_m},
    {"link_work", "J", &CouplingSample::link_work_J},
    {"drift_work", "J", &CouplingSample::drift_work_J},
}};

struct InterfaceOut {
  std::string path;  // /coupling/<link>
  std::array<DatasetHandle, kColumns.size()> columns;
  DatasetHandle force;
  std::array<std::vector<double>, kColumns.size()> buffers;  // [k] each
  std::vector<double> force_buffer;                          // [3k]
};

}  // namespace

struct CouplingHistoryWriter::Impl {
  std::string path;
  FileHandle file;
  std::vector<InterfaceOut> interfaces;
  std::set<std::string> links;
  std::size_t buffered = 0;
  Clock::time_point last_flush = Clock::now();

  Location root() const { return Location{file.get(), path, "/"}; }

  /// Appends the buffered rows; the buffers are emptied even if a write fails (no row is ever
  /// written twice).
  void write_rows() {
    struct Clear {
      Impl* self;
      ~Clear() {
        for (auto& i : self->interfaces) {
          for (auto& b : i.buffers) b.clear();
          i.force_buffer.clear();
        }
        self->buffered = 0;
        self->last_flush = Clock::now();
      }
    } clear{this};
    for (InterfaceOut& i : interfaces) {
      for (std::size_t c = 0; c < kColumns.size(); ++c) {
        append_rows(Location{i.columns[c].get(), path, i.path + "/" + kColumns[c].name},
                    i.buffers[c], 0);
      }
      append_rows(Location{i.force.get(), path, i.path + "/force"}, i.force_buffer, 3);
    }
  }

  void flush_file() {
    if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) {
      throw ResultFileError(path, "/", "H5Fflush (flush the coupling history file to disk)");
    }
  }
};

CouplingHistoryWriter::CouplingHistoryWriter(const std::string& path) {
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->file = create_file(path);
  const Location root = impl->root();
  write_attribute(root, "format", std::string("crashlink-coupling"));
  write_attribute(root, "format_version", std::int64_t{1});
  create_group(root, "coupling");
  impl->flush_file();
  impl_ = std::move(impl);
}

CouplingHistoryWriter::~CouplingHistoryWriter() {
  if (!impl_) return;
  try {
    flush();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crashlink: flushing %s failed: %s\n", impl_->path.c_str(), e.what());
  } catch (...) {
    std::fprintf(stderr, "crashlink: flushing %s failed\n", impl_->path.c_str());
  }
  impl_->interfaces.clear();  // datasets before the file
  if (!impl_->file.close()) {
    std::fprintf(stderr, "crashlink: closing %s failed (H5Fclose)\n", impl_->path.c_str());
  }
}

std::size_t CouplingHistoryWriter::add_interface(const std::string& name, const std::string& kind,
                                                 const std::string& fine, const std::string& coarse,
                                                 const std::string& scheme, std::int64_t j_nodes) {
  Impl& w = *impl_;
  const std::size_t index = w.interfaces.size();
  std::string link = result_link_name(name, "interface", index);
  if (w.links.count(link) != 0) link = fmt::format("{}_{}", link, index);
  while (w.links.count(link) != 0) link += "_";
  w.links.insert(link);

  const Location root = w.root();
  GroupHandle coupling = open_group(root, "coupling");
  const Location cat{coupling.get(), w.path, "/coupling"};
  GroupHandle g = create_group(cat, link);
  InterfaceOut out;
  out.path = cat.child(link);
  const Location at{g.get(), w.path, out.path};
  write_attribute(at, "name", name);
  write_attribute(at, "kind", kind);
  write_attribute(at, "fine", fine);
  write_attribute(at, "coarse", coarse);
  write_attribute(at, "scheme", scheme);
  write_attribute(at, "j_nodes", j_nodes);
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    out.columns[c] = create_extendible(at, kColumns[c].name, 0, kChunkRows, kColumns[c].units);
  }
  out.force = create_extendible(at, "force", 3, kChunkRows, "N");
  w.interfaces.push_back(std::move(out));
  w.flush_file();
  return index;
}

void CouplingHistoryWriter::append(std::size_t iface, const CouplingSample& s) {
  Impl& w = *impl_;
  if (iface >= w.interfaces.size()) {
    throw ResultFileError(w.path, "/coupling",
                          fmt::format("append: interface index {} but {} interface(s) added "
                                      "(pass the index add_interface returned)",
                                      iface, w.interfaces.size()));
  }
  InterfaceOut& i = w.interfaces[iface];
  for (std::size_t c = 0; c < kColumns.size(); ++c) i.buffers[c].push_back(s.*kColumns[c].value);
  i.force_buffer.insert(i.force_buffer.end(), s.force_N, s.force_N + 3);
  ++w.buffered;
  const double wall = std::chrono::duration<double>(Clock::now() - w.last_flush).count();
  if (w.buffered >= kFlushSamples || wall >= kFlushWallSeconds) flush();
}

void CouplingHistoryWriter::write_timing(
    double wall_seconds, double coordinator_cpu_seconds,
    const std::vector<std::pair<std::string, double>>& wait_seconds) {
  Impl& w = *impl_;
  const Location root = w.root();
  GroupHandle timing =
      link_exists(root, "timing") ? open_group(root, "timing") : create_group(root, "timing");
  const Location at{timing.get(), w.path, "/timing"};
  write_attribute(at, "wall_seconds", wall_seconds);
  write_attribute(at, "coordinator_cpu_seconds", coordinator_cpu_seconds);
  for (std::size_t i = 0; i < wait_seconds.size(); ++i) {
    const std::string link = result_link_name(wait_seconds[i].first, "domain", i);
    GroupHandle g = link_exists(at, link) ? open_group(at, link) : create_group(at, link);
    const Location dat{g.get(), w.path, at.child(link)};
    write_attribute(dat, "name", wait_seconds[i].first);
    write_attribute(dat, "wait_seconds", wait_seconds[i].second);
  }
  w.flush_file();
}

void CouplingHistoryWriter::flush() {
  Impl& w = *impl_;
  w.write_rows();
  w.flush_file();
}

const std::string& CouplingHistoryWriter::group_path(std::size_t iface) const {
  if (iface >= impl_->interfaces.size()) {
    throw ResultFileError(impl_->path, "/coupling",
                          fmt::format("interface index {} of {}", iface, impl_->interfaces.size()));
  }
  return impl_->interfaces[iface].path;
}

}  // namespace crashlink::io
