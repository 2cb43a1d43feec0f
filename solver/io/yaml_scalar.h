#pragma once
// Scalar conversions of the scenario reader: exactly yaml-cpp 0.7's YAML::convert<T>::decode of a
// scalar holding `text` (a stream read; integers in base 10, 0x hex or 0 octal; floats also as
// .inf, -.inf, .nan; booleans as YAML 1.1 words), with a fast path for the plain decimal forms
// of long lists (the same value: both round correctly). Internal to crashlink::io.
#include <cstdint>
#include <string_view>

namespace crashlink::io {

bool scalar_to_double(std::string_view text, double& v);
bool scalar_to_int64(std::string_view text, std::int64_t& v);
bool scalar_to_bool(std::string_view text, bool& v);

}  // namespace crashlink::io
