#pragma once
// One received ZeroMQ message: a parsed Envelope, or bytes that are not one (never a crash).
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"

namespace crashlink::transport {

/// The bytes of a received message as they came, kept so that a Router can forward them to
/// another peer without serialising the Envelope again and without a copy (Router::forward: the
/// buffer itself is handed to ZeroMQ). Opaque, movable; empty() when nothing was kept.
class Payload {
 public:
  Payload();
  ~Payload();
  Payload(Payload&&) noexcept;
  Payload& operator=(Payload&&) noexcept;
  bool empty() const { return impl_ == nullptr; }
  std::size_t size() const;  ///< bytes (0 when empty)

  struct Impl;  ///< transport/detail/zmq.h
  explicit Payload(std::unique_ptr<Impl> impl);
  Impl* impl() const { return impl_.get(); }

 private:
  std::unique_ptr<Impl> impl_;
};

struct Received {
  std::string peer;         // Router: the sender's routing id (= domain name for daemons);
                            // Dealer: empty (the only peer is the coordinator)
  wire::Envelope envelope;  // valid when ok()
  std::string error;        // not empty: why the bytes are not an Envelope (size, frames, ...)
  Payload payload;          // Router: the Envelope's bytes when ok() (for Router::forward)
  bool ok() const { return error.empty(); }
};

/// A routing id fit for a message: core::log_escape (printable ASCII as is, every other byte as
/// \xNN, bounded; ZeroMQ's generated ids start with \x00).
std::string printable_peer(std::string_view routing_id);

}  // namespace crashlink::transport
