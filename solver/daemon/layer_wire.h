#pragma once
// cosim::LayerMessage <-> wire Envelope (proto/crashlink.proto, docs/design.md §3 and §2.7):
//   Displacement -> LayerDisplacement {interface_index, time_ticks = T + H,
//                                      displacements_m = u_J(T + H),
//                                      angular_velocities_rad_s = omega_J(T + H/2)}
//   Force        -> LayerForce {interface_index, time_ticks = T, forces_n = g_A(T),
//                               moments_n_m = the layer's moment on J}
// Vectors are copied bit for bit (packed doubles), so a message that crossed a socket is the one
// the in-process LayerNetwork would have delivered.
#include <optional>

#include "proto/crashlink.pb.h"
#include "solver/cosim/layer_stepper.h"

namespace crashlink::daemon {

wire::Envelope to_envelope(const cosim::LayerMessage& m);

/// The LayerMessage in a LayerForce or LayerDisplacement envelope; nullopt for any other message.
std::optional<cosim::LayerMessage> to_layer_message(const wire::Envelope& e);

}  // namespace crashlink::daemon
