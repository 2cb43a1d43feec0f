#include "solver/io/scenario_names.h"

#include <fmt/format.h>

#include "core/log_escape.h"

namespace crashlink::io {

namespace {

bool allowed(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

bool utf8_continuation(unsigned char c) {
  return (c & 0xc0) == 0x80;
}

/// The character starting at byte i, for a message: itself when printable ASCII, else its bytes.
std::string describe(std::string_view name, std::size_t i) {
  const auto c = static_cast<unsigned char>(name[i]);
  if (c >= 0x20 && c < 0x7f) return fmt::format("'{}'", static_cast<char>(c));
  std::size_t end = i + 1;
  if (c >= 0x80)
    while (end < name.size() && utf8_continuation(static_cast<unsigned char>(name[end]))) ++end;
  return fmt::format("{} (byte{} {})", c >= 0x80 ? "a non-ASCII character" : "a control character",
                     end - i > 1 ? "s" : "", core::log_escape(name.substr(i, end - i)));
}

constexpr const char* kRule =
    "a name that becomes a file name is 1 to 64 characters, each an ASCII letter, a digit, '_', "
    "'-' or '.', not starting with '.'";

}  // namespace

std::string safe_file_name(std::string_view name) {
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (utf8_continuation(c)) continue;  // one '_' per multi-byte character
    if (out.empty() && c == '.') continue;
    out += allowed(c) ? ch : '_';
  }
  if (out.size() > kMaxFileNameChars) out.resize(kMaxFileNameChars);
  if (out.empty() || out == "coordinator") out = "domain_" + out;
  return out;
}

std::string file_name_problem(std::string_view name) {
  std::string why;
  if (name.empty()) {
    why = "it is empty";
  } else if (name.size() > kMaxFileNameChars) {
    why = fmt::format("it has {} characters, more than {}", name.size(), kMaxFileNameChars);
  } else if (name.front() == '.') {
    why = "it starts with '.' (a hidden file; '.' and '..' are folders)";
  } else if (name == "coordinator") {
    why = "'coordinator' is the coordinator's own checkpoint folder";
  } else {
    std::size_t position = 0;  // in characters, 1-based
    for (std::size_t i = 0; i < name.size(); ++i) {
      const auto c = static_cast<unsigned char>(name[i]);
      if (!utf8_continuation(c)) ++position;
      if (allowed(c)) continue;
      why = fmt::format("character {}, {}, is not allowed", position, describe(name, i));
      break;
    }
  }
  if (why.empty()) return {};
  return fmt::format("{}: {}; fix: rename it, e.g. '{}'", why, kRule, safe_file_name(name));
}

}  // namespace crashlink::io
