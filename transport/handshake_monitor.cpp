// detail/handshake_monitor.h: socket monitor events of the security handshake.
#include "transport/detail/handshake_monitor.h"

#include <fmt/format.h>

#include <atomic>
#include <cstring>

namespace crashlink::transport::detail {

HandshakeMonitor::HandshakeMonitor(zmq::socket_t& socket, int events)
    : monitored_(socket.handle()) {
  static std::atomic<unsigned> counter{0};
  const std::string endpoint = fmt::format("inproc://crashlink-monitor-{}", counter.fetch_add(1));
  if (zmq_socket_monitor(monitored_, endpoint.c_str(), events) != 0) {
    throw zmq::error_t();
  }
  pair_ = zmq::socket_t(process_context(), zmq::socket_type::pair);
  pair_.set(zmq::sockopt::linger, 0);
  pair_.connect(endpoint);
}

HandshakeMonitor::~HandshakeMonitor() {
  (void)zmq_socket_monitor(monitored_, nullptr, 0);
}

std::vector<HandshakeEvent> HandshakeMonitor::drain() {
  std::vector<HandshakeEvent> out;
  for (;;) {
    zmq::message_t head;
    zmq::recv_result_t got;
    try {
      got = pair_.recv(head, zmq::recv_flags::dontwait);
    } catch (const zmq::error_t&) {
      return out;
    }
    if (!got) return out;
    HandshakeEvent e;
    if (head.size() >= 6) {
      std::uint16_t id = 0;
      std::memcpy(&id, head.data(), sizeof id);
      std::memcpy(&e.value, static_cast<const char*>(head.data()) + 2, sizeof e.value);
      e.event = id;
    }
    // The second frame (the address) always follows the first: wait for it.
    if (head.more()) {
      zmq::message_t address;
      if (pair_.recv(address, zmq::recv_flags::none)) e.address = address.to_string();
    }
    if (e.event != 0) out.push_back(std::move(e));
  }
}

std::string protocol_error_name(std::uint32_t code) {
  switch (code) {
    case ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH:
      return "ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH";
    case ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC:
      return "ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC";
    case ZMQ_PROTOCOL_ERROR_ZMTP_UNEXPECTED_COMMAND:
      return "ZMQ_PROTOCOL_ERROR_ZMTP_UNEXPECTED_COMMAND";
    case ZMQ_PROTOCOL_ERROR_ZMTP_INVALID_SEQUENCE:
      return "ZMQ_PROTOCOL_ERROR_ZMTP_INVALID_SEQUENCE";
    case ZMQ_PROTOCOL_ERROR_ZMTP_MALFORMED_COMMAND_MESSAGE:
      return "ZMQ_PROTOCOL_ERROR_ZMTP_MALFORMED_COMMAND_MESSAGE";
    case ZMQ_PROTOCOL_ERROR_ZAP_BAD_REQUEST_ID:
    case ZMQ_PROTOCOL_ERROR_ZAP_BAD_VERSION:
    case ZMQ_PROTOCOL_ERROR_ZAP_INVALID_STATUS_CODE:
    case ZMQ_PROTOCOL_ERROR_ZAP_MALFORMED_REPLY:
    case ZMQ_PROTOCOL_ERROR_ZAP_UNSPECIFIED:
      return fmt::format("ZAP protocol error 0x{:08x}", code);
    default:
      return fmt::format("ZMTP protocol error 0x{:08x}", code);
  }
}

}  // namespace crashlink::transport::detail
