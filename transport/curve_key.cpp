#include "transport/curve_key.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "transport/curve_errors.h"
#include "transport/detail/zmq.h"

namespace crashlink::transport {

namespace {

constexpr std::string_view kZ85 =
    "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#";

constexpr std::string_view kFix =
    "fix: use the files written by `crashlink keygen --out PREFIX` (PREFIX.key secret, PREFIX.pub "
    "public), one 40-character Z85 key per line, '#' comment lines";

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

/// One line of a key file: a key, nothing (comment, blank), or a problem.
struct Line {
  std::string key;
  std::string problem;
};

Line parse_line(std::string_view raw, bool secret) {
  const std::string_view text = trim(raw);
  if (text.empty()) return {};
  const auto end = std::find_if(text.begin(), text.end(), is_space);
  const std::string_view word = text.substr(0, static_cast<std::size_t>(end - text.begin()));
  const std::string problem = curve_key_problem(word);
  if (problem.empty()) {
    const std::string_view rest = trim(text.substr(word.size()));
    if (!rest.empty() && rest.front() != '#') {
      return {{}, fmt::format("text after the key that is not a '#' comment ('{}')", rest)};
    }
    return {std::string(word), {}};
  }
  if (text.front() == '#') return {};  // a comment
  if (secret) return {{}, fmt::format("not a Z85 key: {}", problem)};
  return {{}, fmt::format("'{}' is not a Z85 key: {}", word, problem)};
}

struct KeyLine {
  std::string key;
  int line = 0;
};

/// Every key of `path` with its line; throws on an unreadable file or a bad line.
std::vector<KeyLine> read_keys(const std::string& path, std::string_view kind, bool secret) {
  std::ifstream in(path);
  if (!in) {
    throw CurveKeyFileError(
        path, 0, std::string(kind),
        fmt::format("cannot open the file ({}); {}", std::strerror(errno), kFix));
  }
  std::vector<KeyLine> keys;
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    const Line line = parse_line(raw, secret);
    if (!line.problem.empty()) {
      throw CurveKeyFileError(path, number, std::string(kind),
                              fmt::format("{}; {}", line.problem, kFix));
    }
    if (!line.key.empty()) keys.push_back({line.key, number});
  }
  if (in.bad()) {
    throw CurveKeyFileError(path, number, std::string(kind), "read error");
  }
  if (keys.empty()) {
    throw CurveKeyFileError(path, number, std::string(kind),
                            fmt::format("no key in the file ({} lines); {}", number, kFix));
  }
  return keys;
}

}  // namespace

std::string curve_key_problem(std::string_view text) {
  if (text.size() != kCurveKeyChars) {
    return fmt::format("{} characters, a Z85 key has {}", text.size(), kCurveKeyChars);
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (kZ85.find(text[i]) == std::string_view::npos) {
      return fmt::format("character {} (code {}) is not in the Z85 alphabet", i + 1,
                         static_cast<int>(static_cast<unsigned char>(text[i])));
    }
  }
  std::array<std::uint8_t, 32> bytes{};
  const std::string copy(text);
  if (zmq_z85_decode(bytes.data(), copy.c_str()) == nullptr) {
    return "a 5-character group is above 2^32 (not the Z85 encoding of any key)";
  }
  return {};
}

std::string read_curve_key_file(const std::string& path, std::string_view kind, bool secret) {
  const auto keys = read_keys(path, kind, secret);
  if (keys.size() > 1) {
    throw CurveKeyFileError(path, keys[1].line, std::string(kind),
                            fmt::format("a second key (the first is on line {}): this file holds "
                                        "exactly one; {}",
                                        keys[0].line, kFix));
  }
  return keys.front().key;
}

std::vector<std::string> read_authorized_keys(const std::string& path) {
  std::vector<std::string> out;
  for (auto& k : read_keys(path, "authorized keys", false)) {
    if (std::find(out.begin(), out.end(), k.key) == out.end()) out.push_back(std::move(k.key));
  }
  return out;
}

std::string curve_public_key(std::string_view secret_z85) {
  if (!curve_key_problem(secret_z85).empty()) {
    throw std::invalid_argument(
        "crashlink::transport: curve_public_key of a text that is not a key");
  }
  const std::string secret(secret_z85);
  std::array<char, kCurveKeyChars + 1> pub{};
  if (zmq_curve_public(pub.data(), secret.c_str()) != 0) {
    throw std::invalid_argument(fmt::format("crashlink::transport: zmq_curve_public failed: {}",
                                            zmq_strerror(zmq_errno())));
  }
  return std::string(pub.data(), kCurveKeyChars);
}

std::string curve_key_text(std::string_view raw32) {
  if (raw32.size() != 32) {
    throw std::invalid_argument(
        fmt::format("crashlink::transport: a CURVE key is 32 bytes, not {}", raw32.size()));
  }
  std::array<char, kCurveKeyChars + 1> text{};
  zmq_z85_encode(text.data(), reinterpret_cast<const std::uint8_t*>(raw32.data()), raw32.size());
  return std::string(text.data(), kCurveKeyChars);
}

}  // namespace crashlink::transport
