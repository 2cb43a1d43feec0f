#pragma once
// CURVE keys in ZeroMQ's Z85 text form (40 characters for 32 bytes) and the files that hold
// them (docs/processes.md, "Security (CURVE)"):
//   secret key file      PREFIX.key of `crashlink keygen`: exactly one key
//   public key file      PREFIX.pub: exactly one key (a daemon's --curve-server-key is the
//                        coordinator's PREFIX.pub)
//   authorized keys      one public key per line (the daemons' PREFIX.pub files concatenated)
// In every file a line is a key when its first word is 40 characters of the Z85 alphabet that
// decode (text after the key must start with '#'); otherwise a line starting with '#' is a
// comment and a blank line is skipped; anything else is a CurveKeyFileError with file and line.
// ('#' is a Z85 character, but no key starts with it: 84 * 85^4 is above 2^32.)
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace crashlink::transport {

inline constexpr std::size_t kCurveKeyChars = 40;

/// Why `text` is not a Z85 key (length, a character outside the alphabet, a 5-character group
/// above 2^32), or "" if it is one.
std::string curve_key_problem(std::string_view text);

/// Reads a file holding exactly one key. `kind` names it in errors ("secret key", "server public
/// key"); a secret key's text is never copied into a message. Throws CurveKeyFileError.
std::string read_curve_key_file(const std::string& path, std::string_view kind, bool secret);

/// Reads an authorized-keys file: at least one public key; duplicates are kept once. Throws
/// CurveKeyFileError.
std::vector<std::string> read_authorized_keys(const std::string& path);

/// The public key of a Z85 secret key (zmq_curve_public). Throws std::invalid_argument for a
/// text that is not a key.
std::string curve_public_key(std::string_view secret_z85);

/// The Z85 text of 32 raw key bytes (a ZAP request's credential).
std::string curve_key_text(std::string_view raw32);

}  // namespace crashlink::transport
