#include "transport/curve_support.h"

#include <fmt/format.h>

#include "transport/curve_errors.h"
#include "transport/detail/zmq.h"

namespace crashlink::transport {

bool curve_available() {
  return zmq_has("curve") != 0;
}

void require_curve(std::string_view purpose) {
  if (curve_available()) return;
  int major = 0, minor = 0, patch = 0;
  zmq_version(&major, &minor, &patch);
  throw CurveUnavailableError(fmt::format(
      "{} needs CURVE, but libzmq {}.{}.{} was built without it (zmq_has(\"curve\") is false); "
      "fix: install a libzmq built with libsodium (Debian 12: apt install libzmq5 libzmq3-dev) "
      "and rebuild crashlink",
      purpose, major, minor, patch));
}

}  // namespace crashlink::transport
