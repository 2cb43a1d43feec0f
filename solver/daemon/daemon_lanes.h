#pragma once
// A daemon's lanes (docs/processes.md "Lanes"): its own, where the partners' vectors arrive (shared
// memory beside an ipc session, a ZeroMQ ROUTER otherwise, CURVE across hosts), and one to each
// partner the Setup lists. A message the scheme addresses to an interface leaves on that
// interface's partner's lane; without lanes everything goes through the coordinator.
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coupling/domain_scheme.h"
#include "proto/crashlink.pb.h"
#include "transport/dealer.h"
#include "transport/router.h"
#include "transport/session.h"
#include "transport/shm_lane.h"

namespace crashlink::daemon {

/// CRASHLINK_INJECT_LANE_DELAY=DOMAIN:MS: that daemon waits MS ms (an integer >= 0) between
/// creating its own lane files and opening its partners' (a test of the lanes' ends,
/// `LaneEnds.*`); 0 for another domain or without the variable. InputError for another form.
std::int64_t injected_lane_delay_ms(const std::string& domain);

class DaemonLanes {
 public:
  DaemonLanes(std::string domain, const transport::SessionOptions& session)
      : domain_(std::move(domain)), session_(session) {}

  /// Opens this daemon's lane beside the coordinator's endpoint. A lane that cannot be opened is
  /// said on stderr and none is offered (the coordinator then routes every vector).
  void open_own(const std::string& coordinator_endpoint);
  /// Our lane (Register.lane_endpoint) and its CURVE public key; "" when none.
  const std::string& endpoint() const { return endpoint_; }
  std::string public_key() const;

  /// The Setup's lanes: a sender to each partner's lane, named by our domain; a shared-memory one
  /// is opened now, waiting up to the peer timeout for the partner's files and calling
  /// `keep_alive` meanwhile (the coordinator must go on hearing this daemon). Throws
  /// ProtocolError when the Setup lists lanes this daemon cannot use or misses a partner's,
  /// TransportError when a partner's files do not appear.
  void connect(const wire::Setup& setup, const std::vector<coupling::LanePartner>& partners,
               const std::function<void()>& keep_alive);
  /// Before this daemon ends: waits until every partner has opened our shared-memory ring, for
  /// at most `timeout`. Our files go with us, and a partner that has not opened them yet would
  /// find none. Between looks it calls `go_on` (the daemon's heartbeats, its stop flag, the
  /// coordinator's Error), and stops waiting when that says false. False when it stopped before
  /// every partner had opened.
  bool hold_until_opened(std::chrono::milliseconds timeout,
                         const std::function<bool()>& go_on) const;
  /// Vectors go daemon to daemon.
  bool active() const { return !out_.empty(); }
  /// Sends on the lane of interface `interface_index`; false when it has none.
  bool send(std::int64_t interface_index, const wire::Envelope& e);
  /// A partner's message within `wait`, or nullopt. Throws ProtocolError for bytes that are not an
  /// Envelope, a sender that is not a partner, or a message `scheme` does not take on a lane.
  std::optional<wire::Envelope> receive(std::chrono::milliseconds wait,
                                        const coupling::DomainScheme& scheme);

 private:
  /// Where one partner's vectors leave: its ZeroMQ lane or its shared-memory lane.
  struct Out {
    std::unique_ptr<transport::Dealer> zmq;
    std::unique_ptr<transport::ShmLaneOut> shm;
  };

  std::string domain_;
  transport::SessionOptions session_;
  std::string endpoint_;                          ///< our lane, or ""
  std::unique_ptr<transport::Router> zmq_in_;     ///< our ZeroMQ lane (loopback tcp, inproc)
  std::unique_ptr<transport::ShmLaneIn> shm_in_;  ///< our shared-memory lane (ipc sessions)
  std::map<std::string, Out> out_;                ///< partner -> its lane
  std::vector<Out*> of_interface_;  ///< [interface index] the lane its vectors leave on
  std::string bytes_;               ///< the last message from the shared-memory lane (reused)
};

}  // namespace crashlink::daemon
