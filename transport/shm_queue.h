#pragma once
// Shared-memory lanes between the daemons of one machine (docs/processes.md "Lanes"): the layer
// vectors of an ipc session go through memory both processes map, not through sockets. A ZeroMQ
// message wakes three threads (the sender's I/O thread, the receiver's I/O thread, the receiver);
// here a message is a memcpy and, only when the receiver sleeps, one futex wake-up.
//
// The receiver creates both files, ShmDoorbell and ShmQueue (write, then rename: a file that
// exists is complete) before it can be sent to; a sender opens them, waiting up to a timeout for
// them to appear, and marks the queue opened. Files are removed by their creator, which keeps
// them until every sender has opened them.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace crashlink::transport {

/// A mapped file (shared, read-write); unmapped (and unlinked if owned) on destruction. The owner
/// (creator) holds a shared flock on it while it lives, so that reclaim_orphan_shm_files can tell
/// the file of a process that died (SIGKILL leaves it behind) from a live one.
class ShmMapping {
 public:
  ShmMapping() = default;
  ShmMapping(std::string path, std::size_t bytes, bool create);
  ~ShmMapping();
  ShmMapping(ShmMapping&& o) noexcept;
  ShmMapping& operator=(ShmMapping&& o) noexcept;
  ShmMapping(const ShmMapping&) = delete;
  ShmMapping& operator=(const ShmMapping&) = delete;

  void* data() const { return data_; }
  std::size_t size() const { return size_; }
  const std::string& path() const { return path_; }
  bool mapped() const { return data_ != nullptr; }

 private:
  void release() noexcept;
  std::string path_;
  void* data_ = nullptr;
  std::size_t size_ = 0;
  bool owner_ = false;
  int lock_fd_ = -1;  ///< owner: the open file that holds the flock
};

/// Removes the files under `dir` named `prefix`* whose owner died: a final name that no process
/// holds a flock on, and a PATH.tmp<pid> of a pid that no longer exists. Returns how many were
/// removed. Never throws. The coordinator calls it at its start (for "/dev/shm", "crashlink-").
/// `ring_names_only`: only names a lane gives its files (PREFIX...bell, PREFIX...from.<domain>,
/// and their .tmp / .orphan forms), for a folder that holds other files too.
std::size_t reclaim_orphan_shm_files(const std::string& dir, const std::string& prefix,
                                     bool ring_names_only = false);

/// One 4 KiB file per receiving daemon, PATH.bell: a futex word every sender bumps after a push,
/// and a flag saying the receiver sleeps on it.
class ShmDoorbell {
 public:
  /// Receiver: creates PATH (replacing a stale one).
  static ShmDoorbell create(const std::string& path);
  /// Sender: opens PATH if it is there and complete; nullopt otherwise.
  static std::optional<ShmDoorbell> open(const std::string& path);

  /// Sender, after a push: wakes the receiver if it sleeps.
  void ring();
  /// Receiver: the current ring count, read before checking the queues.
  std::uint32_t count() const;
  /// Receiver: sleeps until the count differs from `seen` or `timeout` passes (a ring between
  /// count() and sleep() is never lost: the futex compares the word first).
  void sleep(std::uint32_t seen, std::chrono::microseconds timeout);

 private:
  struct Header;
  explicit ShmDoorbell(ShmMapping m) : map_(std::move(m)) {}
  Header& h() const { return *static_cast<Header*>(map_.data()); }
  ShmMapping map_;
};

/// One file per (sender, receiver), PATH.from.<sender>: a ring of length-prefixed byte strings,
/// single producer, single consumer; head (bytes written) and tail (bytes read) are counters that
/// only grow, so full and empty are never confused. The ring holds whole messages only: a message
/// larger than the ring is refused with a TransportError naming the sizes and the fix.
class ShmQueue {
 public:
  static constexpr std::size_t kDefaultCapacity = std::size_t{4} << 20;  // bytes of ring

  /// Receiver: creates PATH with a ring of `capacity` bytes (a power of two >= 4096).
  static ShmQueue create(const std::string& path, std::size_t capacity = kDefaultCapacity);
  /// Sender: opens PATH if it is there and complete; nullopt otherwise.
  static std::optional<ShmQueue> open(const std::string& path);

  /// Sender: appends one message; waits (sleeping 50 us at a time) while the ring is too full,
  /// throws TransportError after `timeout` or if the message can never fit.
  void push(std::string_view bytes, std::chrono::milliseconds timeout);
  /// Receiver: the next message, or nullopt if none is there now.
  std::optional<std::string> pop();
  /// The same into `out` (its capacity reused: no allocation per message once it is large
  /// enough); false if none is there now.
  bool pop_into(std::string& out);
  bool empty() const;
  /// Receiver: whether the sender has opened the file. Until it has, the file must stay (a
  /// receiver that ends removes it): docs/processes.md "Lanes".
  bool opened_by_sender() const;
  const std::string& path() const { return map_.path(); }

 private:
  struct Header;
  explicit ShmQueue(ShmMapping m) : map_(std::move(m)) {}
  Header& h() const { return *static_cast<Header*>(map_.data()); }
  unsigned char* ring() const;
  void copy_in(std::uint64_t at, const void* src, std::size_t n);
  void copy_out(std::uint64_t at, void* dst, std::size_t n) const;
  ShmMapping map_;
};

}  // namespace crashlink::transport
