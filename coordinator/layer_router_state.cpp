// LayerRouter checkpoints (layer_router.h track_state / restore_track).
#include <fmt/format.h>

#include <algorithm>

#include "coordinator/layer_router.h"
#include "solver/core/errors.h"

namespace crashlink::coordinator {

LayerRouter::TrackState LayerRouter::track_state(std::size_t i) const {
  if (i >= tracks_.size()) {
    throw ModelError(fmt::format("layer router: interface {} of {}", i, tracks_.size()));
  }
  const Track& t = tracks_[i];
  if (!t.forces.empty() || !t.displacements.empty()) {
    throw ModelError(
        fmt::format("layer router: interface {} has {} forces and {} displacements "
                    "waiting to be paired; its state is saved between two instants",
                    i, t.forces.size(), t.displacements.size()));
  }
  return TrackState{t.next_force, t.next_displacement, t.g_prev, t.u_prev,
                    t.m_prev,     t.have_prev,         t.work_J};
}

void LayerRouter::restore_track(std::size_t i, TrackState s) {
  if (i >= tracks_.size()) {
    throw ModelError(fmt::format("layer router: interface {} of {}", i, tracks_.size()));
  }
  Track& t = tracks_[i];
  t.forces.clear();
  t.displacements.clear();
  t.next_force = s.next_force;
  t.next_displacement = s.next_displacement;
  t.g_prev = std::move(s.g_prev);
  t.u_prev = std::move(s.u_prev);
  t.m_prev = std::move(s.m_prev);
  t.have_prev = s.have_prev;
  t.work_J = s.work_J;
}

void LayerRouter::restore_progress(Tick time, std::int64_t forwarded) {
  std::fill(latest_.begin(), latest_.end(), time);
  forwarded_ = forwarded;
}

}  // namespace crashlink::coordinator
