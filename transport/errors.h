#pragma once
// Typed errors of the transport and protocol layers (docs/design.md §7 rule 6): each message names
// the endpoint or the peer, the values and, where there is one, the fix.
#include <chrono>
#include <string>

#include "core/errors.h"
#include "proto/crashlink.pb.h"

namespace crashlink::transport {

/// A socket could not do its job: bad endpoint string, bind/connect refused, send queue full, a
/// send to a peer that is not connected. what() = "transport <endpoint>: <cause>".
class TransportError : public crashlink::Error {
 public:
  TransportError(std::string endpoint, std::string cause);
  const std::string& endpoint() const { return endpoint_; }
  const std::string& cause() const { return cause_; }

 private:
  std::string endpoint_;
  std::string cause_;
};

/// A peer that has been silent (no message at all, not even a Heartbeat) for longer than the peer
/// timeout (docs/design.md §3). peer() is the domain name (coordinator side) or "coordinator"
/// (daemon side); endpoint() is where the link is bound or connected. `description` is how the
/// message names the culprit(s), e.g. "domain 'wiper'" or "the coordinator".
class PeerTimeoutError : public TransportError {
 public:
  PeerTimeoutError(std::string endpoint, std::string peer, const std::string& description,
                   std::chrono::milliseconds silent_for, std::chrono::milliseconds timeout);
  const std::string& peer() const { return peer_; }
  std::chrono::milliseconds silent_for() const { return silent_for_; }

 private:
  std::string peer_;
  std::chrono::milliseconds silent_for_;
};

/// The peer sent an Error message (docs/design.md §3): a refused Hello (version or scenario
/// mismatch, unknown domain) or a failure during the run. what() is the peer's text, which gives
/// the values and the fix, escaped (core::log_escape); code() and domain() (escaped) are the
/// message's fields.
class RemoteError : public crashlink::Error {
 public:
  explicit RemoteError(const wire::Error& error);
  wire::ErrorCode code() const { return code_; }
  const std::string& domain() const { return domain_; }

 private:
  wire::ErrorCode code_;
  std::string domain_;
};

/// A wait given up because SessionOptions::stop was set (SIGINT / SIGTERM): not a failure of the
/// peer, the caller ends as stopped on request.
class StopRequested : public crashlink::Error {
 public:
  using crashlink::Error::Error;
};

}  // namespace crashlink::transport
