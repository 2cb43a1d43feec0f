#pragma once
// PRIVATE to the transport library (includes ZeroMQ): the handshake events of one socket, read
// from a ZeroMQ socket monitor (zmq_socket_monitor) over an inproc PAIR of the process-wide
// context. Router and Dealer use it to see a CURVE handshake fail (refused key, wrong server key,
// CURVE on one side only) at once instead of only timing out. Never waits: drain() reads what
// has arrived; socket() can be added to a poll.
#include <cstdint>
#include <string>
#include <vector>

#include "transport/detail/zmq.h"

namespace crashlink::transport::detail {

struct HandshakeEvent {
  int event = 0;  ///< ZMQ_EVENT_HANDSHAKE_*
  std::uint32_t value =
      0;                ///< AUTH: the ZAP status code; PROTOCOL: ZMQ_PROTOCOL_ERROR_*; else errno
  std::string address;  ///< the endpoint libzmq names (connect: the peer; bind: ours)
};

inline constexpr int kHandshakeEvents =
    ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
    ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH;

class HandshakeMonitor {
 public:
  /// Starts monitoring `socket` for `events` (before its bind or connect, to miss nothing).
  HandshakeMonitor(zmq::socket_t& socket, int events = kHandshakeEvents);
  /// Stops monitoring; the monitored socket must still be open.
  ~HandshakeMonitor();
  HandshakeMonitor(const HandshakeMonitor&) = delete;
  HandshakeMonitor& operator=(const HandshakeMonitor&) = delete;

  zmq::socket_t& socket() { return pair_; }
  /// The events that have arrived, oldest first, without waiting.
  std::vector<HandshakeEvent> drain();

 private:
  void* monitored_;
  zmq::socket_t pair_;
};

/// "ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH" and the like, or the number in hex.
std::string protocol_error_name(std::uint32_t code);

}  // namespace crashlink::transport::detail
