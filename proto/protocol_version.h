#pragma once
// Version of the wire protocol in proto/crashlink.proto (DESIGN.md §3). Every connection starts
// with a Hello carrying it; a peer with another version is refused with
// ERROR_CODE_VERSION_MISMATCH. Bump it on any change that an older peer would misread (renumbered
// or retyped fields, new required message in the session); adding an optional field does not need a
// bump.
#include <cstdint>

namespace crashlink::wire {

inline constexpr std::uint32_t kProtocolVersion = 1;

}  // namespace crashlink::wire
