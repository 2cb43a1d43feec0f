#pragma once
// Typed errors of CURVE security (docs/processes.md, "Security (CURVE)"): each names the file and
// line or the endpoint, what is wrong and the fix. The three that the fix is in the invocation
// of are input errors (exit code 2 in every crashlink program, core/exit_codes.h).
#include <string>

#include "core/errors.h"

namespace crashlink::transport {

/// A key file that cannot be used: missing, unreadable, empty, not one Z85 key of 40 characters.
/// what() = "FILE:LINE: KIND: what; fix".
class CurveKeyFileError : public crashlink::InputError {
 public:
  using InputError::InputError;
};

/// CURVE is needed on an endpoint (not loopback, or asked for) and a key file is not given.
/// what() = "transport ENDPOINT: what is missing; fix".
class CurveConfigError : public crashlink::InputError {
 public:
  CurveConfigError(std::string endpoint, const std::string& cause);
  const std::string& endpoint() const { return endpoint_; }

 private:
  std::string endpoint_;
};

/// The coordinator refused this daemon's security handshake: its public key is not authorised,
/// it has the wrong server public key, or one side uses CURVE and the other not. Detected from
/// the socket's handshake events, at once, instead of waiting for the handshake timeout.
/// what() = "transport ENDPOINT: the coordinator refused ...; fix".
class CurveRefusedError : public crashlink::InputError {
 public:
  CurveRefusedError(std::string endpoint, const std::string& cause);
  const std::string& endpoint() const { return endpoint_; }

 private:
  std::string endpoint_;
};

/// This libzmq was built without CURVE (zmq_has("curve") is false).
class CurveUnavailableError : public crashlink::Error {
 public:
  using Error::Error;
};

}  // namespace crashlink::transport
