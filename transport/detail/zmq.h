#pragma once
// PRIVATE to the transport library (docs/design.md §5: only the transport layer includes ZeroMQ
// headers): included by transport/*.cpp and the transport unit tests, never by a public header.
//
// Debian installs cppzmq in /usr/include, a system directory, so its warnings are not shown. If
// it comes from a non-system prefix, cppzmq 4.9 trips our -Wold-style-cast (one C cast, inline in
// zmq.hpp) under -Werror: the push/pop exempts only cppzmq's own lines.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#include <zmq.hpp>
#include <zmq_addon.hpp>
#pragma GCC diagnostic pop

#include <chrono>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"
#include "transport/received.h"
#include "transport/socket_options.h"

namespace crashlink::transport {

struct Payload::Impl {
  zmq::message_t message;
};

}  // namespace crashlink::transport

namespace crashlink::transport::detail {

/// The process-wide ZeroMQ context: every Router and Dealer uses it, which is what lets inproc://
/// endpoints pair. Created on first use (1 I/O thread); terminated at exit after every socket has
/// closed (unsent messages wait at most SocketOptions::linger_ms).
zmq::context_t& process_context();

/// Linger, high-water marks, send timeout, maximum message size.
void configure(zmq::socket_t& socket, const SocketOptions& options);

/// The Envelope as one ZeroMQ message, serialized in place (no intermediate buffer).
zmq::message_t serialize(const wire::Envelope& envelope);

/// Parses one message into `envelope`; on failure returns a description (size, first bytes) and
/// leaves `envelope` cleared. An Envelope with no body set counts as a failure (random bytes can
/// parse as a message of unknown fields only).
std::string parse(const zmq::message_t& message, wire::Envelope& envelope);

/// Waits until `socket` has a message or `timeout` passes (0: just look). EINTR counts as
/// "nothing yet". Returns true when readable.
bool wait_readable(zmq::socket_t& socket, std::chrono::milliseconds timeout);

}  // namespace crashlink::transport::detail
