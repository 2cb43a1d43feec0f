#include "coordinator/coupling_history.h"

#include <utility>

#include "solver/io/coupling_history_reader.h"
#include "solver/io/coupling_history_writer.h"

namespace crashlink::coordinator {

struct CouplingHistory::Impl {
  explicit Impl(const std::string& path) : writer(path) {}
  io::CouplingHistoryWriter writer;
  std::vector<std::size_t> slot;  // [interfaces] the writer's index
};

CouplingHistory::CouplingHistory(std::string path, const LayerCut& cut, const std::string& scheme)
    : path_(std::move(path)), impl_(std::make_unique<Impl>(path_)) {
  for (const auto& c : cut.interfaces) {
    impl_->slot.push_back(
        impl_->writer.add_interface(c.name, c.kind, cut.names[static_cast<std::size_t>(c.fine)],
                                    cut.names[static_cast<std::size_t>(c.coarse)], scheme,
                                    static_cast<std::int64_t>(c.j_node_ids.size())));
  }
}

void CouplingHistory::append(std::uint32_t interface,
                             const std::vector<coupling::LayerSample>& rows,
                             std::int64_t ticks_per_second) {
  for (const auto& r : rows) {
    io::CouplingSample s;
    s.time_s = static_cast<double>(r.time) / static_cast<double>(ticks_per_second);
    s.velocity_jump_m_s =
        0.0;  // the ghosts follow the owner: no jump, no gap (docs/design.md §2.7)
    s.displacement_gap_m = 0.0;
    s.link_work_J = r.link_work_J;
    s.drift_work_J = 0.0;
    for (std::size_t d = 0; d < 3; ++d) s.force_N[d] = r.force_N[d];
    if (impl_) impl_->writer.append(impl_->slot[interface], s);
  }
}

void CouplingHistory::append(const std::vector<PaperRow>& rows, std::int64_t ticks_per_second) {
  for (const auto& r : rows) {
    io::CouplingSample s;
    s.time_s = static_cast<double>(r.time) / static_cast<double>(ticks_per_second);
    s.velocity_jump_m_s = r.velocity_jump_m_s;
    s.displacement_gap_m = r.displacement_gap_m;
    s.link_work_J = r.link_work_J;
    s.drift_work_J = r.drift_work_J;
    for (std::size_t d = 0; d < 3; ++d) s.force_N[d] = r.force_N[d];
    if (impl_) impl_->writer.append(impl_->slot[r.interface], s);
  }
}

std::size_t CouplingHistory::replay(const std::string& from, double until_s) {
  std::size_t rows = 0;
  if (!impl_) return rows;
  for (const std::size_t slot : impl_->slot) {
    for (const auto& s : io::read_coupling_rows(from, impl_->writer.group_path(slot))) {
      if (!(s.time_s <= until_s)) break;
      impl_->writer.append(slot, s);
      ++rows;
    }
  }
  impl_->writer.flush();
  return rows;
}

void CouplingHistory::flush() {
  if (impl_) impl_->writer.flush();
}

void CouplingHistory::finish(double wall_seconds, double cpu_seconds,
                             const std::vector<DomainOutcome>& domains) {
  if (!impl_) return;
  std::vector<std::pair<std::string, double>> waits;
  for (const auto& d : domains) waits.emplace_back(d.name, d.wait_seconds);
  impl_->writer.write_timing(wall_seconds, cpu_seconds, waits);
  impl_->writer.flush();
  impl_.reset();  // closes the file
}

CouplingHistory::~CouplingHistory() = default;

}  // namespace crashlink::coordinator
