#pragma once
// Strings that came from another process (a routing id, a domain name in a Hello, the text of an
// Error, a Bye's reason, a lane's name) are escaped before they reach a log line or a message
// that gets printed: a peer must not be able to write its own lines into our log (a newline and
// a forged "done: all domains finished") or drive the terminal (escape sequences).
//
// The rule, one place for every process (docs/processes.md "Strings from the network"):
// printable ASCII (0x20-0x7e) as is, except the backslash; every other byte (control characters,
// newlines, DEL, non-ASCII bytes, also of valid UTF-8) and the backslash as \xNN (two lower-case
// hex digits), so that the escaped text is one line of printable ASCII that says exactly which
// bytes came. At most `max_bytes` bytes of the input are shown; a longer input ends with
// "...(+N bytes)".
#include <cstddef>
#include <string>
#include <string_view>

namespace crashlink::core {

/// Default bound for a name or an id (domain names are at most 64 characters, routing ids 255).
inline constexpr std::size_t kLogNameBytes = 128;
/// Default bound for a free text (an Error's message, a Bye's reason).
inline constexpr std::size_t kLogTextBytes = 2048;

/// `bytes` fit for one log line (see above).
std::string log_escape(std::string_view bytes, std::size_t max_bytes = kLogNameBytes);

}  // namespace crashlink::core
