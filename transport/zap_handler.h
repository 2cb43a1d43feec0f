#pragma once
// The process's ZAP handler (ZeroMQ RFC 27) for CURVE server sockets (docs/processes.md,
// "Security (CURVE)"): libzmq asks it, over inproc://zeromq.zap.01 of the process-wide context,
// whether a client's CURVE public key may connect. One handler serves every CURVE Router of the
// process, each under its own ZAP domain with its own authorized keys. It runs on its own thread,
// started by the first ZapDomain and stopped (woken, unbound, joined) when the last one goes.
// Refused clients are recorded (key, peer address) for the coordinator's log.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace crashlink::transport {

/// One refused CURVE client.
struct CurveRefusal {
  std::string address;     ///< the peer's address as libzmq gives it (tcp: IP), "" if none
  std::string client_key;  ///< its public key, Z85
  std::string text;        ///< names the peer and the key, says why and the fix
};

/// A CURVE server socket's entry in the ZAP handler: set name() as the socket's ZMQ_ZAP_DOMAIN
/// before binding. Not copyable or movable (hold it in a unique_ptr).
class ZapDomain {
 public:
  /// `authorized`: Z85 public keys; `keys_file`: where they come from (for messages).
  /// `later`: the keys come with authorize(); a client asking before then waits for them (up to
  /// 10 s, then refused).
  ZapDomain(std::vector<std::string> authorized, std::string keys_file, bool later = false);
  /// Sets the authorized keys (and ends the wait of a `later` domain).
  void authorize(std::vector<std::string> keys);
  ~ZapDomain();
  ZapDomain(const ZapDomain&) = delete;
  ZapDomain& operator=(const ZapDomain&) = delete;

  const std::string& name() const;
  /// The refusals since the last call (at most 1000 are kept between calls).
  std::vector<CurveRefusal> take_refusals();
  /// Clients accepted so far.
  std::uint64_t accepted() const;

  struct State;

 private:
  std::shared_ptr<State> state_;
};

}  // namespace crashlink::transport
