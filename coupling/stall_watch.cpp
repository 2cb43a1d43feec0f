#include "coupling/stall_watch.h"

namespace crashlink::coupling {

bool StallWatch::stuck(const std::vector<Tick>& latest, std::size_t finished,
                       Clock::time_point now) {
  if (!started_ || latest != seen_ || finished != finished_) {
    started_ = true;
    seen_ = latest;
    finished_ = finished;
    last_move_ = now;
  }
  still_for_ = now - last_move_;
  return still_for_ > limit_;
}

}  // namespace crashlink::coupling
