#pragma once
// Reads a result.h5 back (layout: docs/result-format.md, contract: docs/design.md §4): probe and
// contact histories, glstat, the mesh's ids, field states and timing. Used by `crashlink hic`, the
// plot tools and the gather of a coupled run's per-domain files (solver/gather).
//
// Array layouts: ProbeHistory::displacement_m, velocity_m_s, acceleration_m_s2 are [3k]
// interleaved xyz, sample i at 3i..3i+2 (the [k,3] datasets as stored); time_s is [k].
// ContactHistory::force_N [3k] likewise. StateData::displacement_m, velocity_m_s [3n] (file node
// order); PartStateData::eps_p, von_mises_Pa [ne], stress_Pa [6ne] (file element order).
//
// A run killed during a flush may leave a probe's datasets with different row counts: the reader
// keeps the rows all of them have (the common prefix). HDF5 failures throw ResultFileError
// (solver/io/hdf5_handles.h); a probe that is not in the file throws InputError listing the
// probes the file has.
#include <cstdint>
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

/// One contact's history: resultant force on the slave side, global frame, and the interface's
/// contact energy (below zero: energy the contact created).
struct ContactHistory {
  std::string name;  ///< the user's name (group attribute "name"; the link name if absent)
  std::string link;  ///< HDF5 group name under /history/contacts
  std::vector<double> time_s;    ///< [k]
  std::vector<double> force_N;   ///< [3k]
  std::vector<double> energy_J;  ///< [k]; empty in files written before the dataset existed
  std::size_t size() const { return time_s.size(); }
};

/// One part of /mesh/parts.
struct MeshPartInfo {
  std::string name;                       ///< attribute "name" (the link name if absent)
  std::string link;                       ///< group name under /mesh/parts
  std::string kind;                       ///< "hex8" or "shell4" ("" if absent)
  std::int64_t index = 0;                 ///< attribute "index": model order
  std::int64_t id = 0;                    ///< attribute "id": a deck's *PART PID (0: none)
  std::vector<std::int64_t> element_ids;  ///< [ne]
};

/// Element results of one part in one state; an empty vector: not in the file.
struct PartStateData {
  std::string link;                  ///< group name under /states/<k>/parts
  std::vector<double> eps_p;         ///< [ne]
  std::vector<double> von_mises_Pa;  ///< [ne]
  std::vector<double> stress_Pa;     ///< [6ne]
};

/// One field state /states/<k>; velocity_m_s empty if the file has none.
struct StateData {
  double time_s = 0.0;
  std::vector<double> displacement_m;  ///< [3n]
  std::vector<double> velocity_m_s;    ///< [3n] or empty
  std::vector<PartStateData> parts;    ///< the parts the state has results for (link order)
};

/// /timing: present = false if the file has none (a run that died before writing it).
struct TimingData {
  bool present = false;
  double wall_seconds = 0.0;
  double coordinator_cpu_seconds = 0.0;
  std::vector<DomainTiming> domains;  ///< /timing/<domain> groups, link order
};

/// The first k rows of a history as the writer takes them (ResultWriter::append_probe_rows /
/// append_contact_rows): what the gather and a restart copy from one file into another. A contact
/// history without energy (an older file) gives energy_J = NaN: not known, not 0.
std::vector<ProbeSample> probe_samples(const ProbeHistory& h, std::size_t k);
std::vector<ContactSample> contact_samples(const ContactHistory& h, std::size_t k);

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

  /// The contacts' user names under /history/contacts, in link order.
  std::vector<std::string> contact_names() const;
  /// The contact with this user name or link name (rows: the common prefix of time, force and
  /// energy if present); throws InputError naming the contacts the file has if there is none.
  ContactHistory contact(const std::string& name) const;
  /// The rigid walls' user names under /history/rigid_walls (none in files of models without
  /// walls, or written before 2026-11-27).
  std::vector<std::string> wall_names() const;
  /// The rigid wall with this user name or link name: its force on the nodes it stops and, in
  /// energy_J, its work on them (/history/rigid_walls/<name>/work); InputError if there is none.
  ContactHistory wall(const std::string& name) const;

  /// /mesh/node_ids [n].
  std::vector<std::int64_t> node_ids() const;
  /// /mesh/parts, in model order (attribute "index").
  std::vector<MeshPartInfo> mesh_parts() const;

  /// Complete field states: the /states attribute "count" (0 if absent).
  std::size_t state_count() const;
  /// The "time" attribute of /states/<k>.
  double state_time(std::size_t k) const;
  /// /states/<k> (k < state_count()); throws ResultFileError if it is incomplete.
  StateData state(std::size_t k) const;

  /// /timing and its /timing/<domain> groups.
  TimingData timing() const;
  /// /events/spot_weld_failures in the order written (empty if the file has none).
  std::vector<SpotWeldFailure> spot_weld_failures() const;

 private:
  ContactHistory item_history(bool wall, const std::string& name) const;
  struct Impl;
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::io
