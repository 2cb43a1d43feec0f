#pragma once
// What a daemon says and checks between its Hello and its run (docs/processes.md "The session"):
// the Register it sends, and the check that the coordinator's Setup is for the same scheme.
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/domain_scheme.h"
#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"

namespace crashlink::daemon {

/// The Lane a daemon offers in its Register (empty: none).
struct OfferedLane {
  std::string endpoint;
  std::string public_key;
};

/// The Register of the domain `scheme` runs: its proposed step in ticks of `ticks_per_second`
/// (coupling::proposal_ticks with `options`), its end time, element count, the instants of its
/// intact checkpoints, its lane, and what the scheme adds (its interfaces).
wire::Envelope register_message(const coupling::DomainScheme& scheme,
                                const coupling::DomainSchemeOptions& options,
                                std::int64_t ticks_per_second,
                                const std::vector<coupling::Tick>& checkpoint_instants,
                                const OfferedLane& lane);

/// Both sides must run the same scheme: a `layer` daemon cannot serve a `paper` coordinator.
/// Throws ProtocolError naming both schemes and the fix.
void check_scheme(const wire::Setup& setup, const std::string& domain, const std::string& scheme);

}  // namespace crashlink::daemon
