#pragma once
// Daemon end of the session (session.h) over a Dealer whose routing id names this connection:
// "<domain>#<16 random hex digits>" (session_routing_id), so that a second daemon started for the
// same domain is a second connection, which the coordinator refuses without touching the first
// (ZeroMQ would hand the first one's routing id over to it: ROUTER_HANDOVER, router.h).
// Use: DaemonLink. One thread at a time.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>

#include "proto/crashlink.pb.h"
#include "transport/dealer.h"
#include "transport/session.h"

namespace crashlink::transport {

/// A fresh routing id for a session of `domain`: its first 200 bytes, '#', 16 random hex digits.
std::string session_routing_id(std::string_view domain);

///   DaemonLink link(endpoint, daemon_hello("wiper", hash));   // handshake; throws on refusal
///   link.send(register_envelope);
///   while (auto m = link.receive(5s)) { ... }                 // Setup, Correction, ..., Bye
///   link.bye("end time reached");
/// A daemon busy computing for longer than the heartbeat interval calls keep_alive() now and then.
/// One thread at a time.
class DaemonLink {
 public:
  /// Connects to `endpoint` as hello.domain() and performs the handshake: sends the Hello and
  /// waits for the coordinator's answer, its Hello (coordinator_hello(), with ticks_per_second) or
  /// an Error, thrown as RemoteError whose text is the coordinator's (both values and the fix for a
  /// version or scenario mismatch). Throws RemoteError (the coordinator refused: version,
  /// scenario, unknown domain), TransportError (no answer within options.handshake_timeout, bad
  /// endpoint) or ProtocolError (an answer that is not a Hello).
  DaemonLink(std::string_view endpoint, const wire::Hello& hello,
             const SessionOptions& options = {});

  const std::string& endpoint() const { return dealer_.endpoint(); }
  const std::string& domain() const { return domain_; }
  const std::string& routing_id() const { return dealer_.routing_id(); }
  const wire::Hello& coordinator_hello() const { return coordinator_hello_; }
  /// False after a Bye or Error was sent or received.
  bool open() const { return open_; }

  /// Sends one Envelope; a Bye or an Error ends the session. Throws TransportError.
  void send(const wire::Envelope& envelope);
  /// Reports a failure of this daemon to the coordinator and ends the session. Never waits: the
  /// Error is queued if the connection can take it (the socket's linger delivers it at close),
  /// and dropped if the coordinator is gone or not reading (its own timeout tells it). A blocking
  /// send here held a stopped daemon the send timeout (5 s) when the coordinator had ended first.
  void send_error(wire::ErrorCode code, std::string message);
  /// Ends the session cleanly.
  void bye(std::string reason);

  /// The next message from the coordinator other than a Heartbeat, or nullopt after `timeout`
  /// (0: do not wait); swallows Heartbeats and sends its own when idle. A Bye is returned and ends
  /// the session. Throws RemoteError (the coordinator sent an Error), PeerTimeoutError naming the
  /// coordinator's endpoint (coordinator silent for the peer timeout), ProtocolError (bytes that
  /// are not an Envelope, a Hello mid-session, session ended).
  std::optional<wire::Envelope> receive(std::chrono::milliseconds timeout);

  /// Sends a Heartbeat if nothing was sent for the heartbeat interval, and throws
  /// PeerTimeoutError if the coordinator has been silent for the peer timeout. Cheap (a clock
  /// read); call it from long computations.
  void keep_alive();

 private:
  using Clock = std::chrono::steady_clock;
  /// Throws PeerTimeoutError when nothing came for the peer timeout, after reading what waits in
  /// the socket (kept for receive()): a process that was not scheduled for that long (a loaded
  /// machine) finds the coordinator's heartbeats queued, and must not call it dead.
  void check_coordinator(Clock::time_point now);
  /// A received message: nullopt for a Heartbeat, the Envelope otherwise (a Bye ends the
  /// session); throws for an Error, bytes that are not an Envelope, a second Hello.
  std::optional<wire::Envelope> accept(Received& r);
  void send_heartbeat_if_idle(Clock::time_point now);

  SessionOptions options_;
  std::string domain_;
  Dealer dealer_;
  wire::Hello coordinator_hello_;
  Clock::time_point last_heard_;
  Clock::time_point last_sent_;
  bool open_ = false;
  std::uint64_t heartbeat_sequence_ = 0;
  wire::Envelope heartbeat_;
  std::deque<wire::Envelope> inbox_;  ///< read by check_coordinator, for receive()
};

}  // namespace crashlink::transport
