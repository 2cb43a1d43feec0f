#pragma once
// One received ZeroMQ message: a parsed Envelope, or bytes that are not one (never a crash).
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"

namespace crashlink::transport {

struct Received {
  std::string peer;         // Router: the sender's routing id (= domain name for daemons);
                            // Dealer: empty (the only peer is the coordinator)
  wire::Envelope envelope;  // valid when ok()
  std::string error;        // not empty: why the bytes are not an Envelope (size, frames, ...)
  bool ok() const { return error.empty(); }
};

/// A routing id fit for a message: printable ASCII as is, otherwise "0x" + hex (ZeroMQ's
/// generated ids start with a zero byte).
std::string printable_peer(std::string_view routing_id);

}  // namespace crashlink::transport
