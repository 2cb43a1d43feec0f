#pragma once
// Whether this libzmq can do CURVE (built with libsodium or its own tweetnacl).
#include <string_view>

namespace crashlink::transport {

/// zmq_has("curve").
bool curve_available();

/// Throws CurveUnavailableError naming `purpose`, the libzmq version and the fix, unless
/// curve_available().
void require_curve(std::string_view purpose);

}  // namespace crashlink::transport
