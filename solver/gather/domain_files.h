#pragma once
// The per-domain result files of a coupled run, opened for the gather (gather_results.h):
// DIR/domains/<domain>.h5 (io::ResultWriter, file_stem = the domain's link name), with the maps
// from the file's rows to the global model: node rows to global node indices (by user id) and
// whether the domain owns the node (not a ghost, not a copy), local parts to global parts (by
// name) and local elements to elements of the global part (by user id).
//
// Array layouts: DomainFile::row_global, row_owned [n_file] (file node order);
// DomainFile::Part::element [ne_file] (file element order of that part).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/gather/gather_results.h"
#include "solver/io/result_reader.h"

namespace crashlink::gather {

struct DomainFile {
  std::string name;                        ///< domain name
  int domain = -1;                         ///< index into Decomposition::domains
  std::string path;                        ///< the file read (or the one looked for)
  std::optional<io::ResultReader> reader;  ///< empty: absent or unusable (see GatherReport)
  std::vector<io::GlstatSample> glstat;    ///< its /history/glstat (may be empty)
  std::vector<double> state_times;         ///< [states] time of each complete field state [s]
  std::vector<std::int32_t> row_global;    ///< [n_file] global node index of each file row
  std::vector<std::uint8_t> row_owned;     ///< [n_file] 1: the domain owns the node
  struct Part {
    std::string link;  ///< group name under /mesh/parts and /states/<k>/parts
    int global_part = -1;
    std::vector<std::int32_t> element;  ///< [ne_file] index in the global part
  };
  std::vector<Part> parts;
};

/// DIR/domains/<link>.h5 (or, if absent, DIR/domains/<link>/result.h5) of domain `name`.
std::string domain_file_path(const std::string& dir, const std::string& name, std::size_t index);

/// Opens the file of every non-empty domain of `dec` (decomposition order; absent or unusable
/// ones come back without a reader and are listed in report.missing with the reason in
/// report.notes; the readable ones in report.domains_read) and reads their glstat, state times
/// and maps. Throws io::ResultFileError or ModelError (when the file's ids do not belong to
/// `global`/`dec`) only if no file at all is usable.
std::vector<DomainFile> open_domain_files(const model::Model& global,
                                          const partition::Decomposition& dec,
                                          const std::string& dir, GatherReport& report);

}  // namespace crashlink::gather
