#pragma once
// A daemon's check of the coordinator's Setup (docs/design.md §2.7 "How to distribute layer", §3):
// the tick must be the Hello's, the step >= 1, and every interface of this domain's own cut must
// be in it with the same side and partner; the fine side then takes its owner's step from it
// (as cosim::LayerNetwork plans it). Separate from daemon.cpp so that the fuzz target
// tests/fuzz/daemon_fuzz.cpp runs the very check the daemon runs.
#include <cstdint>
#include <string>
#include <vector>

#include "proto/crashlink.pb.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::daemon {

/// Sets LayerPort::partner_step of every fine port of `ports` from `setup`. Throws
/// ProtocolError (peer "coordinator") naming the domain, the values and the likely
/// cause when the Setup does not fit.
void apply_setup(const wire::Setup& setup, std::int64_t ticks_per_second, const std::string& domain,
                 std::vector<cosim::LayerPort>& ports);

}  // namespace crashlink::daemon
