#pragma once
// `crashlink advise --process-sample F` (issue #5: "advise predicts the measured gain"): the
// gain of the scenario's own split measured on the real thing over a short stretch of the run.
// The counts-and-steps prediction and the in-process sample leave out what processes cost (the
// messages through the coordinator, the ZeroMQ hand-offs, the coordinator itself); this runs the
// scene in mono and in multi over processes (ipc, as `crashlink run`) to F and to 2F of its end
// time and takes the gain from the differences, which cancels what every run pays once (reading,
// cutting, initialising, starting processes, writing the files):
//   gain = (CPU_mono(2F) - CPU_mono(F)) / (CPU_multi(2F) - CPU_multi(F)),
// CPU_multi counting the daemons and the coordinator. It costs four short runs (about 3F of the
// mono run in all).
#include <string>

namespace crashlink::apps {

struct ProcessSample {
  double fraction = 0.0;           ///< F
  double gain = 0.0;               ///< as above
  double coordinator_share = 0.0;  ///< coordinator CPU / multi CPU over [F, 2F]
  double mono_cpu_s = 0.0;         ///< CPU_mono(2F) - CPU_mono(F)
  double multi_cpu_s = 0.0;        ///< CPU_multi(2F) - CPU_multi(F)
};

/// Runs the four sample runs into a temporary folder (removed afterwards) with the given step
/// safety. Throws InputError when F is not in (0, 0.5], the scenario has fewer than two domains or
/// a sample run fails (its exit code and folder in the message).
ProcessSample sample_on_processes(const std::string& scenario, double fraction, double step_safety);

}  // namespace crashlink::apps
