#pragma once
// Where a daemon binds its lane (docs/processes.md "Lanes"): the ROUTER on which its `layer`
// partners send it their vectors directly, daemon to daemon, instead of through the coordinator.
// Derived from the coordinator's endpoint, so that a lane stays where the session is:
//   inproc://NAME          -> inproc://NAME.lane.<domain>
//   ipc://PATH             -> shm:///dev/shm/crashlink-<hash of PATH>.<domain> (shared memory,
//                             shm_lane.h; shm://PATH.<domain> where there is no /dev/shm)
//   tcp://LOOPBACK:PORT    -> tcp://LOOPBACK:* (ephemeral port, read back after the bind)
//   any other tcp, or CURVE forced -> no lane (""): the coordinator routes that daemon's vectors.
//   (A lane across hosts would need its own CURVE keys: not done yet.)
#include <string>
#include <string_view>

#include "transport/curve_options.h"

namespace crashlink::transport {

std::string lane_endpoint_for(std::string_view coordinator_endpoint, std::string_view domain,
                              const CurveOptions& curve);

}  // namespace crashlink::transport
