#pragma once
// Where a daemon binds its lane (docs/processes.md "Lanes"): the ROUTER on which its `layer`
// partners send it their vectors directly, daemon to daemon, instead of through the coordinator.
// Derived from the coordinator's endpoint, so that a lane stays where the session is:
//   inproc://NAME          -> inproc://NAME.lane.<domain>
//   ipc://PATH             -> shm:///dev/shm/crashlink-<hash of PATH>.<domain> (shared memory,
//                             shm_lane.h; shm://PATH.<domain> where there is no /dev/shm)
//   tcp://LOOPBACK:PORT    -> tcp://LOOPBACK:* (ephemeral port, read back after the bind)
//   tcp://HOST:PORT        -> tcp://LOCAL:* where LOCAL is this host's address on the route to
//                             HOST (across hosts, containers, network namespaces); CURVE on, with
//                             this daemon's keys as server and its partners' from the Setup
//   CURVE forced on a local session, or no route to HOST -> no lane (""): the coordinator routes
//   that daemon's vectors.
#include <string>
#include <string_view>

#include "transport/curve_options.h"

namespace crashlink::transport {

/// This host's address (text; IPv6 in brackets) on the route to `host`:`port`, "" if none.
std::string local_address_towards(const std::string& host, const std::string& port);

std::string lane_endpoint_for(std::string_view coordinator_endpoint, std::string_view domain,
                              const CurveOptions& curve);

}  // namespace crashlink::transport
