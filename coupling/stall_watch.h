#pragma once
// A run that no longer moves although every process is alive (docs/design.md: "a dead or silent
// peer is detected and named"; this is the third case, a schedule that deadlocked). Heartbeats keep
// flowing between processes that all wait for each other, so the peer timeouts never fire; the
// coordinator watches the domains' instants instead (LayerReport every quarter heartbeat from every
// daemon between cycles, FreeState in `paper` runs, Bye at the end). When none of them has changed
// for `limit`, the run is stuck: the coordinator stops it with the domains' last instants.
//
// A domain that is computing cannot be silent that long: it reports between cycles, and a cycle
// longer than the peer timeout already ends the run by that timeout. So the limit is set from the
// peer timeout (coordinator_run.cpp: twice it), and a healthy run never reaches it.
#include <chrono>
#include <cstddef>
#include <vector>

#include "coupling/ticks.h"

namespace crashlink::coupling {

class StallWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit StallWatch(Clock::duration limit) : limit_(limit) {}

  /// The domains' latest instants and how many have finished, at time `now`. Returns true when
  /// neither has changed for longer than the limit (the run is stuck).
  bool stuck(const std::vector<Tick>& latest, std::size_t finished, Clock::time_point now);

  /// How long nothing has moved, as of the last call.
  Clock::duration still_for() const { return still_for_; }

 private:
  Clock::duration limit_;
  std::vector<Tick> seen_;
  std::size_t finished_ = 0;
  bool started_ = false;
  Clock::time_point last_move_{};
  Clock::duration still_for_{};
};

}  // namespace crashlink::coupling
