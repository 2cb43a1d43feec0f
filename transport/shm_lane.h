#pragma once
// A daemon's shared-memory lane (shm_queue.h; docs/processes.md "Lanes"), for daemons that share
// a machine (an ipc session): lane endpoint "shm://PREFIX".
//   receiving end (ShmLaneIn): PREFIX.bell, and PREFIX.from.<partner> for every partner;
//   sending end (ShmLaneOut): opens the partner's PREFIX.from.<self> and PREFIX.bell (open(), or
//   the first send; the partner creates them once it has its Setup), then pushes and rings.
// A receiver that ends keeps its files until every sender has opened them (all_opened()): a
// partner still running may send one last vector its owner step began with, which nobody reads,
// but whose files must be there to open.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "transport/shm_queue.h"

namespace crashlink::transport {

inline constexpr std::string_view kShmScheme = "shm://";

/// Removes a shared-memory lane's files (PREFIX.bell, PREFIX.from.<partner>) if they are still
/// there: the coordinator's clean-up after a run whose daemon was killed. Never throws.
void remove_shm_lane_files(std::string_view endpoint, const std::vector<std::string>& partners);

class ShmLaneIn {
 public:
  /// Creates PREFIX.bell. `spin`: how long receive() polls before it sleeps on the bell.
  explicit ShmLaneIn(std::string prefix,
                     std::chrono::microseconds spin = std::chrono::microseconds{0});
  const std::string& endpoint() const { return endpoint_; }  ///< "shm://PREFIX"
  /// Creates PREFIX.from.<domain> with a ring of at least `capacity` bytes (rounded up to a power
  /// of two, never less than ShmQueue::kDefaultCapacity).
  void add_partner(const std::string& domain, std::size_t capacity = 0);
  /// The next message (sender's domain, bytes), or nullopt after `timeout`.
  std::optional<std::pair<std::string, std::string>> receive(std::chrono::microseconds timeout);
  /// The same into `from` and `bytes`, whose capacities are reused (no allocation per message:
  /// a fresh buffer of a large vector would be fresh pages, a page fault each); false after
  /// `timeout`.
  bool receive_into(std::chrono::microseconds timeout, std::string& from, std::string& bytes);
  /// Whether every partner's sending end has opened its queue.
  bool all_opened() const;

 private:
  bool poll_once(std::string& from, std::string& bytes);
  std::string prefix_, endpoint_;
  std::chrono::microseconds spin_;
  ShmDoorbell bell_;
  std::vector<std::pair<std::string, ShmQueue>> queues_;  ///< (partner, its queue)
  std::size_t next_ = 0;                                  ///< round robin
};

class ShmLaneOut {
 public:
  /// `endpoint` "shm://PREFIX" of the partner; `self` this daemon's domain; `timeout` bounds the
  /// wait for the partner's files and for room in its ring.
  ShmLaneOut(std::string_view endpoint, std::string self, std::chrono::milliseconds timeout);
  /// Opens the partner's files, waiting up to the timeout for them to appear (calling `between`,
  /// if given, between looks: a daemon's heartbeats); TransportError after it. send() calls it
  /// when the files are not open yet.
  void open(const std::function<void()>& between = {});
  void send(std::string_view bytes);
  /// Serialises `message` into a buffer kept for the next one, then send().
  template <class Message>
  void send_message(const Message& message) {
    message.SerializeToString(&buffer_);
    send(buffer_);
  }

 private:
  std::string buffer_;
  std::string prefix_, self_;
  std::chrono::milliseconds timeout_;
  std::optional<ShmQueue> queue_;
  std::optional<ShmDoorbell> bell_;
};

}  // namespace crashlink::transport
