#include "transport/curve_errors.h"

#include <fmt/format.h>

#include <utility>

namespace crashlink::transport {

CurveConfigError::CurveConfigError(std::string endpoint, const std::string& cause)
    : InputError(fmt::format("transport {}: {}", endpoint, cause)),
      endpoint_(std::move(endpoint)) {}

CurveRefusedError::CurveRefusedError(std::string endpoint, const std::string& cause)
    : InputError(fmt::format("transport {}: {}", endpoint, cause)),
      endpoint_(std::move(endpoint)) {}

}  // namespace crashlink::transport
