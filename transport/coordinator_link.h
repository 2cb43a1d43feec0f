#pragma once
// Coordinator end of the session (session.h) over a Router: the table of peers (routing id =
// domain name -> last heard, last sent), the Hello handshake, heartbeats, dead peers, Bye/Error.
// The main loop and the sessions: CoordinatorLink; what a poll answers, swallows and returns:
// CoordinatorLink::poll. One thread at a time.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "proto/crashlink.pb.h"
#include "transport/router.h"
#include "transport/session.h"

namespace crashlink::transport {

struct CoordinatorConfig {
  std::string scenario_hash;          // the daemons' Hello must carry the same
  std::vector<std::string> domains;   // the domains that may join
  std::int64_t ticks_per_second = 0;  // announced in the coordinator's Hello
  SessionOptions options;
};

/// A message from a joined domain.
struct Incoming {
  std::string domain;
  wire::Envelope envelope;
  Payload payload;  ///< the envelope's bytes as received (forward()); empty if not kept
};

/// Something the link refused or dropped, for the log: a refused Hello, garbage bytes, a message
/// before the Hello or after a Bye, a failed heartbeat.
struct Notice {
  std::string peer;  // printable routing id
  std::string text;  // names the peer and says what happened
};

/// Main loop sketch:
///   CoordinatorLink link(endpoint, {hash, {"car", "wiper"}, ticks_per_second});
///   link.await_all_joined(30s);                       // handshakes; early messages are queued
///   while (...) {
///     if (auto in = link.poll(100ms)) { ... in->domain, in->envelope ... link.send(d, reply); }
///     link.check_alive();                             // throws PeerTimeoutError naming the domain
///   }
/// Sessions: a daemon's routing id names its connection (DaemonLink: "<domain>#<random>"), the
/// Hello names its domain. A domain is held by one session at a time: a Hello for a domain whose
/// session is open, or that seal() closed, is refused (ERROR_CODE_DOMAIN_HELD) and the running
/// session is not touched. drop() ends a session from this side and frees its domain.
/// Every string of a peer in a notice or an error text is escaped (core::log_escape).
/// One thread at a time.
class CoordinatorLink {
 public:
  /// Binds `endpoint` (tcp://127.0.0.1:* is resolved, see endpoint()). Throws TransportError.
  CoordinatorLink(std::string_view endpoint, CoordinatorConfig config);

  const std::string& endpoint() const { return router_.endpoint(); }
  const CoordinatorConfig& config() const { return config_; }

  /// The next message of a joined domain, or nullopt after `timeout` (0: do not wait) or as soon
  /// as a new domain has joined (see all_joined()). Meanwhile it answers Hellos, swallows
  /// Heartbeats and sends its own; it returns every other message of a joined domain (Register,
  /// FreeState, LayerForce, LayerDisplacement, Bye, Error). An Error from a daemon comes back with
  /// Error.domain filled in: `throw RemoteError(in->envelope.error())` reports it with the
  /// domain's name. Refused Hellos and bytes that are not Envelopes are answered with an Error to
  /// the sender and recorded as notices (take_notices()), never thrown; so are the daemons the
  /// CURVE handshake refused (Router::take_refusals(): their key and address).
  std::optional<Incoming> poll(std::chrono::milliseconds timeout);

  /// Sends to a joined domain. Sending Bye or Error ends that domain's session (no more
  /// heartbeats, no liveness check). Throws TransportError (domain not joined or not connected).
  void send(std::string_view domain, const wire::Envelope& envelope);

  /// Sends a received message on to a joined domain: its bytes as they came (Incoming::payload,
  /// consumed: no serialisation, no copy), or the envelope serialised when no bytes were kept.
  /// For the messages the coordinator routes unchanged (LayerForce, LayerDisplacement). Throws
  /// as send().
  void forward(std::string_view domain, Incoming& message);

  /// Whether `domain` has completed its handshake and not ended its session.
  bool joined(std::string_view domain) const;
  bool all_joined() const;
  /// Configured domains that have not joined (yet), in configuration order.
  std::vector<std::string> missing() const;
  /// Polls until every domain has joined; messages arriving meanwhile are kept for poll().
  /// Throws TransportError naming the missing domains after `timeout`.
  void await_all_joined(std::chrono::milliseconds timeout);

  /// Joined domains silent for longer than the peer timeout (or the silence allowed to them),
  /// in configuration order.
  std::vector<std::string> dead_peers() const;
  /// From now on `domain` may stay silent for `timeout` (if longer than the peer timeout): its
  /// daemon reached the end time and writes its results, which on a loaded machine or a slow disk
  /// (HDF5 close, fsync, large fields) can take longer than the peer timeout; a daemon that dies
  /// then is still named, after `timeout`.
  void allow_silence(std::string_view domain, std::chrono::milliseconds timeout);
  /// Throws PeerTimeoutError naming every dead domain (dead_peers()), if any, after reading what
  /// waits in the socket (kept for poll()): a coordinator that was not scheduled for the peer
  /// timeout (a loaded machine) finds the daemons' heartbeats queued and must not call them dead.
  void check_alive();

  /// No new session for `domain` from now on (its daemon registered: the run counts on that
  /// session, also after its Bye): a Hello for it is refused with ERROR_CODE_DOMAIN_HELD.
  void seal(std::string_view domain);
  /// Ends `domain`'s open session from this side: sends it an Error with `code` and `text` (best
  /// effort), records a notice, and frees the domain for a new Hello (unless sealed). No effect
  /// on a domain without an open session.
  void drop(std::string_view domain, wire::ErrorCode code, const std::string& text);

  /// The notices recorded since the last call (at most 1000 are kept; older ones are counted).
  std::vector<Notice> take_notices();
  std::uint64_t dropped_notices() const { return dropped_notices_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Peer {
    std::string routing_id;  // the connection of the domain's latest session
    Clock::time_point joined;
    Clock::time_point last_heard;
    Clock::time_point last_sent;
    bool active = false;                           // handshake done and no Bye/Error since
    std::chrono::milliseconds allowed_silence{0};  // allow_silence(); 0: the peer timeout
  };

  std::optional<Incoming> handle(Received& received, Clock::time_point now);
  void handshake(const std::string& routing_id, const wire::Hello& hello, Clock::time_point now);
  /// ERROR_CODE_DOMAIN_HELD when `domain` has an open session or is sealed, else nullopt.
  std::optional<wire::Error> check_free(const std::string& domain, Clock::time_point now) const;
  void reply_error(const std::string& routing_id, wire::ErrorCode code, const std::string& text);
  void send_heartbeats(Clock::time_point now);
  Clock::time_point next_heartbeat() const;
  void notice(const std::string& routing_id, std::string text);
  void collect_refusals();

  CoordinatorConfig config_;
  Router router_;
  std::unordered_map<std::string, Peer> peers_;                // domain -> its latest session
  std::unordered_map<std::string, std::string> domain_of_;     // routing id -> domain (latest only)
  std::unordered_map<std::string, Clock::time_point> sealed_;  // domain -> when seal()ed
  std::deque<Incoming> queued_;
  std::vector<Notice> notices_;
  std::uint64_t dropped_notices_ = 0;
  std::uint64_t heartbeat_sequence_ = 0;
  std::uint64_t joins_ = 0;  // accepted handshakes so far
  wire::Envelope heartbeat_;
};

}  // namespace crashlink::transport
