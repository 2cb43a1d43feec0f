#pragma once
// The coordinator's record of a coupled run. `paper`: per interface the rows of its own exchange
// (paper_exchange.h). `layer`: per interface the rows the fine side reports
// (LayerReport, coupling/layer_work.h: velocity jump and displacement gap 0 by construction,
// link work, drift work 0, resultant layer force) and, at the end, /timing (wall, the coordinator's
// CPU, each daemon's time spent waiting), written through io::CouplingHistoryWriter to
// DIR/coordinator.h5 (gathered into result.h5 under /coupling/<interface>/ and /timing).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/layer_cut.h"
#include "coordinator/paper_exchange.h"
#include "coupling/layer_work.h"

namespace crashlink::coordinator {

class CouplingHistory {
 public:
  /// Creates the file and one group per interface of the cut, marked with the scheme ("layer" or
  /// "paper"). Throws io::ResultFileError.
  CouplingHistory(std::string path, const LayerCut& cut, const std::string& scheme = "layer");
  ~CouplingHistory();
  CouplingHistory(const CouplingHistory&) = delete;
  CouplingHistory& operator=(const CouplingHistory&) = delete;

  void append(std::uint32_t interface, const std::vector<coupling::LayerSample>& rows,
              std::int64_t ticks_per_second);
  /// `paper`: rows of the coordinator's own exchange (gap, jump, link and drift work, force).
  void append(const std::vector<PaperRow>& rows, std::int64_t ticks_per_second);
  /// Restart: copies every interface's rows with time <= until_s from `from` (the checkpoint's
  /// copy of coordinator.h5, same cut), then flushes. Returns the rows copied.
  std::size_t replay(const std::string& from, double until_s);
  /// Writes the buffered rows to disk (before the file is copied into a checkpoint).
  void flush();
  /// /timing, flush, close.
  void finish(double wall_seconds, double cpu_seconds, const std::vector<DomainOutcome>& domains);
  const std::string& path() const { return path_; }

 private:
  struct Impl;
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::coordinator
