#pragma once
// The gather of a coupled run: every daemon wrote DIR/domains/<domain>.h5 for its own sub-model
// (io::ResultWriter with ResultWriterOptions::file_stem = the domain name; node and element ids
// are the global user ids, part names the global part names, ghost nodes present) and the
// coordinator DIR/coordinator.h5 (io::CouplingHistoryWriter). gather_results writes DIR/result.h5
// and DIR/result.xdmf for the global model in the layout of a mono run; the rules are on
// gather_results and in full in docs/result-format.md "Gathered results".
#include <cstdint>
#include <string>
#include <vector>

#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::gather {

struct GatherReport {
  std::vector<std::string> domains_read;  ///< domains whose file was read (decomposition order)
  std::vector<std::string> missing;       ///< non-empty domains whose file is absent or unusable
  double end_time_s = 0;                  ///< time of the last gathered history row [s]
  std::int64_t history_samples = 0;       ///< /history/glstat rows written
  std::int64_t states = 0;                ///< field states written
  std::vector<std::string> notes;         ///< what was incomplete or approximated, one per line
};

/// Reads DIR/domains/<name>.h5 of every non-empty domain of `dec` and DIR/coordinator.h5 (if
/// present) and writes DIR/result.h5 and DIR/result.xdmf for the global model (the same layout as a
/// mono run's, docs/result-format.md). `dec` must be the decomposition the run used
/// (partition::decompose(global, scheme)). Throws io::ResultFileError (no domain file could be
/// read, or the output cannot be written) or ModelError (no domain file belongs to this model),
/// naming the files. The rules:
///   /mesh              the global model's mesh, as a mono run writes it;
///   /history/glstat    sum over the domains, each domain's series interpolated linearly onto the
///                      sample times of the domain with the fewest samples, up to the earliest last
///                      sample time among the domains; energy_balance_error recomputed from the
///                      sums;
///   /history/probes    each probe from the domain that holds it (owner of its node, not a ghost
///                      there; or the domain of its rigid body), with that domain's sample times;
///   /history/contacts  each contact from the domain holding it, with that domain's sample times;
///   /states/<k>        node fields of every global node from its owner domain, element fields of
///                      every global part assembled from the domains' local parts by element id;
///   /timing, /coupling from the domain files' /timing and coordinator.h5.
/// A missing, unreadable or shorter domain file is merged as far as it goes and reported
/// (GatherReport::missing, notes; root attribute gather_notes); nothing is thrown for it.
GatherReport gather_results(const model::Model& global, const partition::Decomposition& dec,
                            const std::string& out_dir);

}  // namespace crashlink::gather
