#include "transport/errors.h"

#include <fmt/format.h>

#include <utility>

#include "core/log_escape.h"

namespace crashlink::transport {

namespace {

double seconds(std::chrono::milliseconds t) {
  return static_cast<double>(t.count()) * 1e-3;
}

// The peer's strings are escaped: this text is printed (core::log_escape).
std::string remote_text(const wire::Error& e) {
  std::string code = wire::ErrorCode_Name(e.code());
  if (code.empty()) code = fmt::format("error code {}", static_cast<int>(e.code()));
  const std::string message = core::log_escape(e.message(), core::kLogTextBytes);
  if (e.domain().empty()) return fmt::format("{}: {}", code, message);
  return fmt::format("{} (domain '{}'): {}", code, core::log_escape(e.domain()), message);
}

}  // namespace

TransportError::TransportError(std::string endpoint, std::string cause)
    : Error(fmt::format("transport {}: {}", endpoint, cause)),
      endpoint_(std::move(endpoint)),
      cause_(std::move(cause)) {}

PeerTimeoutError::PeerTimeoutError(std::string endpoint, std::string peer,
                                   const std::string& description,
                                   std::chrono::milliseconds silent_for,
                                   std::chrono::milliseconds timeout)
    : TransportError(std::move(endpoint),
                     fmt::format("{} silent for {:.3f} s (peer timeout {:.3f} s): no message and "
                                 "no heartbeat; the process died, hangs or the network is down",
                                 description, seconds(silent_for), seconds(timeout))),
      peer_(std::move(peer)),
      silent_for_(silent_for) {}

RemoteError::RemoteError(const wire::Error& error)
    : Error(remote_text(error)), code_(error.code()), domain_(core::log_escape(error.domain())) {}

}  // namespace crashlink::transport
