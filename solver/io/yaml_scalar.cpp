#include "solver/io/yaml_scalar.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <string>

namespace crashlink::io {

namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

/// -?[0-9]+(\.[0-9]*)?([eE][+-]?[0-9]+)?: what both std::from_chars and the stream read take
/// whole, with the same correctly rounded value.
bool plain_decimal(std::string_view s) {
  std::size_t i = s.size() > 0 && s[0] == '-' ? 1 : 0;
  const std::size_t digits = i;
  while (i < s.size() && is_digit(s[i])) ++i;
  if (i == digits) return false;
  if (i < s.size() && s[i] == '.')
    for (++i; i < s.size() && is_digit(s[i]);) ++i;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const std::size_t exponent = i;
    while (i < s.size() && is_digit(s[i])) ++i;
    if (i == exponent) return false;
  }
  return i == s.size();
}

template <class T>
bool yaml_cpp_decode(std::string_view text, T& v) {
  return YAML::convert<T>::decode(YAML::Node(std::string(text)), v);
}

}  // namespace

bool scalar_to_double(std::string_view s, double& v) {
  if (plain_decimal(s)) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec == std::errc() && r.ptr == s.data() + s.size()) return true;
  }
  return yaml_cpp_decode(s, v);  // out of range, .inf, 0x..., quoted spaces, ...
}

bool scalar_to_int64(std::string_view s, std::int64_t& v) {
  // -?[1-9][0-9]{0,17} (no overflow) or 0; a leading 0 means octal to the stream read.
  const std::size_t sign = s.size() > 0 && s[0] == '-' ? 1 : 0;
  const std::size_t n = s.size() - sign;
  if (n >= 1 && n <= 18 && s[sign] >= '1' && s[sign] <= '9') {
    std::int64_t x = 0;
    std::size_t i = sign;
    for (; i < s.size() && is_digit(s[i]); ++i) x = 10 * x + (s[i] - '0');
    if (i == s.size()) {
      v = sign ? -x : x;
      return true;
    }
  } else if (s == "0") {
    v = 0;
    return true;
  }
  return yaml_cpp_decode(s, v);
}

bool scalar_to_bool(std::string_view s, bool& v) {
  return yaml_cpp_decode(s, v);
}

}  // namespace crashlink::io
