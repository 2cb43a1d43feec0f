#pragma once
// What an exception that ends a daemon or the coordinator means (docs/processes.md "Exit codes"):
// its exit code (core/exit_codes.h), the Error code the peers are told, and the text. One
// ladder for both processes: each catches first what only it handles (a daemon: the coordinator's
// Error, a refused CURVE handshake; the coordinator: a stop it decided), then this.
#include <string>

#include "proto/crashlink.pb.h"

namespace crashlink::transport {

struct Failure {
  int exit_code = 0;
  wire::ErrorCode code = wire::ERROR_CODE_INTERNAL;
  std::string text;  ///< "<kind>: <what>" ("I/O error: ...", "model error: ...", or the message)
};

/// Call inside a catch block: the exception in flight as a Failure. crashlink's typed errors map
/// to their codes (NumericalError 3, InputError and ModelError 2, IoError and filesystem errors 6,
/// ProtocolError, TransportError and PeerTimeoutError 5, StopRequested 7); anything else is
/// internal (4).
Failure current_failure();

}  // namespace crashlink::transport
