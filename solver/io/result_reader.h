#pragma once
// Reads the time histories of a result.h5 back (layout: docs/result-format.md, contract:
// DESIGN.md §4): probe histories and glstat. Used by `crashlink hic` and the plot tools.
//
// Array layouts: ProbeHistory::displacement_m, velocity_m_s, acceleration_m_s2 are [3k]
// interleaved xyz, sample i at 3i..3i+2 (the [k,3] datasets as stored); time_s is [k].
//
// A run killed during a flush may leave a probe's datasets with different row counts: the reader
// keeps the rows all of them have (the common prefix). HDF5 failures throw ResultFileError
// (solver/io/hdf5_handles.h); a probe that is not in the file throws InputError listing the
// probes the file has.
#include <memory>
#include <string>
#include <vector>

#include "solver/io/result_writer.h"  // GlstatSample

namespace crashlink::io {

/// One probe's history (node or rigid-body centre of mass), global frame, SI units.
struct ProbeHistory {
  std::string name;  ///< the user's name (group attribute "name"; the link name if absent)
  std::string link;  ///< HDF5 group name under /history/probes ('/' replaced by '_')
  std::string kind;  ///< "node" or "rigid_body" ("" if the attribute is absent)
  std::vector<double> time_s;             ///< [k]
  std::vector<double> displacement_m;     ///< [3k]
  std::vector<double> velocity_m_s;       ///< [3k]
  std::vector<double> acceleration_m_s2;  ///< [3k]
  std::size_t size() const { return time_s.size(); }
};

/// Opens DIR/result.h5 read-only. Not thread-safe (serial HDF5); may be used while a writer in
/// another process is appending (it sees the rows flushed so far).
class ResultReader {
 public:
  /// Throws ResultFileError if the file cannot be opened as HDF5 or is not a crashlink result
  /// (root attribute format != "crashlink-result").
  explicit ResultReader(const std::string& h5_path);
  ResultReader(const ResultReader&) = delete;
  ResultReader& operator=(const ResultReader&) = delete;
  ResultReader(ResultReader&&) noexcept;
  ResultReader& operator=(ResultReader&&) noexcept;
  ~ResultReader();

  const std::string& path() const { return path_; }
  /// The root attribute "model" ("" if absent).
  std::string model_name() const;

  /// The probes' user names, in the file's link order (alphabetical by link name).
  std::vector<std::string> probe_names() const;
  bool has_probe(const std::string& name) const;
  /// The probe with this user name or link name; throws InputError naming the probes the file
  /// has if there is none.
  ProbeHistory probe(const std::string& name) const;

  /// /history/glstat, one row per sample (energy_balance_error 0 if the file has none).
  std::vector<GlstatSample> glstat() const;

 private:
  struct Impl;
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::io
