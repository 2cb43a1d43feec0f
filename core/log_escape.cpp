#include "core/log_escape.h"

#include <fmt/format.h>

namespace crashlink::core {

std::string log_escape(std::string_view bytes, std::size_t max_bytes) {
  const std::size_t shown = bytes.size() < max_bytes ? bytes.size() : max_bytes;
  std::string out;
  out.reserve(shown + 16);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      out += fmt::format("\\x{:02x}", c);
    }
  }
  if (shown < bytes.size()) out += fmt::format("...(+{} bytes)", bytes.size() - shown);
  return out;
}

}  // namespace crashlink::core
