#include "solver/io/coupling_history_reader.h"

#include <algorithm>

#include "solver/io/hdf5_handles.h"

namespace crashlink::io {

std::vector<CouplingSample> read_coupling_rows(const std::string& file,
                                               const std::string& group_path) {
  FileHandle f = open_file_read(file);
  const Location root{f.get(), file, "/"};
  GroupHandle g = open_group(root, group_path.substr(1));
  const Location at{g.get(), file, group_path};
  std::size_t k[6] = {0, 0, 0, 0, 0, 0};
  const auto t = read_doubles(at, "time", 0, &k[0]);
  const auto jump = read_doubles(at, "velocity_jump", 0, &k[1]);
  const auto gap = read_doubles(at, "displacement_gap", 0, &k[2]);
  const auto link = read_doubles(at, "link_work", 0, &k[3]);
  const auto drift = read_doubles(at, "drift_work", 0, &k[4]);
  const auto force = read_doubles(at, "force", 3, &k[5]);
  const std::size_t rows = *std::min_element(std::begin(k), std::end(k));
  std::vector<CouplingSample> out(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    auto& s = out[i];
    s.time_s = t[i];
    s.velocity_jump_m_s = jump[i];
    s.displacement_gap_m = gap[i];
    s.link_work_J = link[i];
    s.drift_work_J = drift[i];
    for (std::size_t d = 0; d < 3; ++d) s.force_N[d] = force[3 * i + d];
  }
  return out;
}

}  // namespace crashlink::io
