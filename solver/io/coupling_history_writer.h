#pragma once
// The coordinator's interface-history file DIR/coordinator.h5 (layout: docs/result-format.md,
// "coordinator.h5"): one group /coupling/<name> per coupling interface with its time histories
// (velocity jump, displacement gap, cumulative link and drift work, force), and /timing with the
// run's wall and coordinator CPU time and the time each domain was seen waiting. The gather of a
// coupled run (solver/gather/gather_results.h) copies /coupling into DIR/result.h5.
//
// Robustness as io::ResultWriter: rows are buffered and written every kFlushSamples samples (over
// all interfaces) or kFlushWallSeconds of wall time, each time followed by H5Fflush, so a
// coordinator that dies leaves every row up to the last flush. Datasets are extendible, chunked
// and unfiltered. The destructor flushes and closes, never throws. HDF5 failures throw
// ResultFileError (solver/io/hdf5_handles.h) naming the file and the object.
//
// Array layouts: CouplingSample::force_N [3] xyz, global frame; /coupling/<name>/force [k,3].
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace crashlink::io {

/// One row of an interface's history at the coordinator's instant time_s.
struct CouplingSample {
  double time_s;              ///< [s]
  double velocity_jump_m_s;   ///< [m/s] velocity jump across the interface
  double displacement_gap_m;  ///< [m] displacement gap between the two sides' interface nodes
  double link_work_J;         ///< [J] cumulative work of the link forces
  double drift_work_J;        ///< [J] cumulative work of the drift correction ([11] of Bourel 2005)
  double force_N[3];          ///< [N] resultant interface force, global frame
};

/// Not thread-safe (nor is serial HDF5): one thread owns the writer.
class CouplingHistoryWriter {
 public:
  /// Buffered rows are written after this many samples (all interfaces together) ...
  static constexpr std::size_t kFlushSamples = 1000;
  /// ... or this much wall time since the last flush.
  static constexpr double kFlushWallSeconds = 5.0;

  /// Creates (truncates) the file with its root attributes and an empty /coupling group. Throws
  /// ResultFileError.
  explicit CouplingHistoryWriter(const std::string& path);
  CouplingHistoryWriter(const CouplingHistoryWriter&) = delete;
  CouplingHistoryWriter& operator=(const CouplingHistoryWriter&) = delete;
  ~CouplingHistoryWriter();  ///< flushes and closes; never throws (failures go to stderr)

  /// Creates /coupling/<name>/ (the name sanitised like other link names, io::result_link_name;
  /// a repeated name gets "_<index>" appended; the original is kept in attribute "name") with
  /// attributes kind ("link", "contact:<name>", ...), fine, coarse (domain names), scheme
  /// ("layer" | "paper"), j_nodes (count) and empty datasets. Returns the index for append().
  std::size_t add_interface(const std::string& name, const std::string& kind,
                            const std::string& fine, const std::string& coarse,
                            const std::string& scheme, std::int64_t j_nodes);
  /// The HDF5 group of interface `iface` ("/coupling/<link>"), what read_coupling_rows reads.
  const std::string& group_path(std::size_t iface) const;
  /// Buffers one row of interface `iface` (an index add_interface returned; ResultFileError
  /// otherwise); may flush.
  void append(std::size_t iface, const CouplingSample& s);
  /// Writes (or replaces) /timing attributes wall_seconds, coordinator_cpu_seconds and
  /// /timing/<domain> attributes name, wait_seconds (time the coordinator saw the domain waiting,
  /// may be 0); flushes.
  void write_timing(double wall_seconds, double coordinator_cpu_seconds,
                    const std::vector<std::pair<std::string, double>>& wait_seconds);
  /// Writes the buffered rows and H5Fflush-es the file.
  void flush();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::io
