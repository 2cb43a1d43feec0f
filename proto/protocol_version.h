#pragma once
// Version of the wire protocol in proto/crashlink.proto (docs/design.md §3). Every connection
// starts with a Hello carrying it; a peer with another version is refused with
// ERROR_CODE_VERSION_MISMATCH. Bump it on any change that an older peer would misread (renumbered
// or retyped fields, new required message in the session); adding an optional field does not need a
// bump.
#include <cstdint>

namespace crashlink::wire {

// History: 1 first version; 2 `layer` processes: Setup.step_ticks,
// LayerInterface.partner_step_ticks, Register.layer_interfaces, the rotational vectors of
// LayerForce / LayerDisplacement, Bye.report; 3 checkpoints and restart: Register.checkpoint_ticks,
// Setup.restart / restart_ticks (a version-2 daemon would start from t = 0 in a restarted run);
// 4 lanes: Register.lane_endpoint / lane_public_key, Setup.lanes; 5 `paper` over processes:
// FreeState.velocities_m_s / energy_time_ticks, EnergyTerms.coupled_kinetic_j (a version-4 daemon
// would cut the scenario for `layer` and misread a `paper` Setup); 6 variable `layer` steps:
// Setup.variable_steps, LayerForce.step_proposal_ticks, LayerDisplacement.last (a version-5
// daemon would run fixed steps against partners that do not); 7 checkpoints of variable `layer`
// steps: LayerDisplacement.pause, LayerReport.checkpoint (a version-6 holder would not pause with
// its owner, and the checkpoint instants would differ); 8 the scheme by name: Setup.scheme instead
// of the Coupling enum (a version-7 daemon would read every Setup as "unspecified"); 9 `lts`:
// Setup.base_ticks (a version-8 daemon would not know the scheme nor its energy instants).
inline constexpr std::uint32_t kProtocolVersion = 9;

}  // namespace crashlink::wire
