#pragma once
// The `paper` rows of `crashlink sweep` (issue #5: "multi with each coupling scheme (layer; paper
// with drift correction on and off)"): the scene under cosim::PaperRunner in this process, at
// the step ratio `multi` plans for it (the `layer` plan's H/h, h under 0.9 of both domains'
// stable steps), sampled as a result file would be (every history interval): CPU, HIC15 and peak
// of the headform after CFC 1000, the displacement probe's peak. The runner's guard ends a run
// that goes unstable ("the coupling went unstable", no NaN kept): the row says when. Without
// drift correction the copies may wander off their originals without any energy growth: the
// largest gaps are reported, so that such a run is not read as a valid one.
#include <string>

#include "solver/model/model.h"

namespace crashlink::apps {

struct PaperSceneResult {
  bool finished = false;
  std::string stopped;  ///< why the run ended early (the guard's or the cut's message)
  double stopped_at_s = 0.0;
  double ratio = 0.0;  ///< H/h run
  double cpu_s = 0.0, wall_s = 0.0;
  double hic15 = 0.0, peak_g = 0.0, disp_m = 0.0;
  double max_link_gap_m = 0.0;  ///< largest distance between a link node's two presences
  double max_copy_gap_m = 0.0;  ///< ... and between a contact copy and its original
};

/// `head_probe`: a rigid-body probe name ("" for none); `disp_probe`: a node probe ("" none).
PaperSceneResult run_paper_scene(const model::Model& m, bool drift, const std::string& head_probe,
                                 const std::string& disp_probe);

}  // namespace crashlink::apps
