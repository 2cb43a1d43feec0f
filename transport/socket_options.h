#pragma once
// Socket settings shared by Router and Dealer (docs/design.md §3: "set linger, poll with
// timeouts").
#include <cstdint>

#include "transport/curve_options.h"

namespace crashlink::transport {

struct SocketOptions {
  /// How long unsent messages (a last Bye or Error) may keep the process-wide context alive at
  /// exit, ms. Closing a socket never blocks; only the context's termination at exit waits. To a
  /// connected peer a message leaves within microseconds on loopback and within a round trip
  /// across hosts; what is still unsent after 100 ms has a peer that is gone (every piece told
  /// to stop at once: 500 ms here made one stop in ten take 0.5 s, 2 s on a loaded machine).
  int linger_ms = 100;
  /// High-water marks, messages (one message = one Envelope). A session has at most a few
  /// messages in flight per peer; 1000 leaves room for bursts without unbounded memory.
  int send_hwm = 1000;
  int receive_hwm = 1000;
  /// A send that cannot queue for this long (peer's queue at the high-water mark) throws
  /// TransportError instead of blocking forever, ms.
  int send_timeout_ms = 5000;
  /// Larger incoming messages are dropped by ZeroMQ (and the connection closed): a bound on what
  /// garbage can make us allocate. 256 MiB is 11 million interface nodes' 3-vectors.
  std::int64_t max_message_bytes = std::int64_t{256} << 20;
  /// CURVE keys (curve_policy.h: on for every non-loopback tcp endpoint, or when forced).
  CurveOptions curve;
};

}  // namespace crashlink::transport
