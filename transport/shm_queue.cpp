#include "transport/shm_queue.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/futex.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <new>
#include <thread>
#include <utility>

#include "transport/errors.h"

namespace crashlink::transport {

namespace {

constexpr std::uint64_t kBellMagic = 0x6c6c6562'6b6e696cULL;   // "linkbell"
constexpr std::uint64_t kQueueMagic = 0x65757571'6b6e696cULL;  // "linkqueu"
constexpr std::size_t kHeaderBytes = 4096;

std::string errno_text(int e) {
  return fmt::format("{} (errno {})", std::strerror(e), e);
}

long futex(std::atomic<std::uint32_t>* word, int op, std::uint32_t value, const timespec* timeout) {
  // Not FUTEX_PRIVATE: the word is in memory shared by two processes.
  return ::syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(word), op, value, timeout, nullptr,
                   0);
}

}  // namespace

ShmMapping::ShmMapping(std::string path, std::size_t bytes, bool create)
    : path_(std::move(path)), size_(bytes), owner_(create) {
  // The creator writes PATH.tmp<pid> and renames it: a file under PATH is always complete.
  const std::string file = create ? fmt::format("{}.tmp{}", path_, ::getpid()) : path_;
  const int fd = ::open(
      file.c_str(), create ? (O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC) : (O_RDWR | O_CLOEXEC), 0600);
  if (fd < 0) {
    throw TransportError("shm://" + path_,
                         fmt::format("cannot open {}: {}", file, errno_text(errno)));
  }
  if (create && ::ftruncate(fd, static_cast<off_t>(bytes)) != 0) {
    const int e = errno;
    ::close(fd);
    throw TransportError("shm://" + path_,
                         fmt::format("cannot size {} to {} bytes: {}", file, bytes, errno_text(e)));
  }
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  const int e = errno;
  if (create && p != MAP_FAILED && ::flock(fd, LOCK_SH | LOCK_NB) == 0) {
    lock_fd_ = fd;  // held until release(): the mark of a live owner
  } else {
    ::close(fd);
  }
  if (p == MAP_FAILED) {
    throw TransportError("shm://" + path_,
                         fmt::format("cannot map {} ({} bytes): {}", file, bytes, errno_text(e)));
  }
  data_ = p;
}

void ShmMapping::release() noexcept {
  if (data_ != nullptr) ::munmap(data_, size_);
  if (owner_) ::unlink(path_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);
  data_ = nullptr;
  owner_ = false;
  lock_fd_ = -1;
}

ShmMapping::~ShmMapping() {
  release();
}

ShmMapping::ShmMapping(ShmMapping&& o) noexcept
    : path_(std::move(o.path_)),
      data_(std::exchange(o.data_, nullptr)),
      size_(o.size_),
      owner_(std::exchange(o.owner_, false)),
      lock_fd_(std::exchange(o.lock_fd_, -1)) {}

ShmMapping& ShmMapping::operator=(ShmMapping&& o) noexcept {
  if (this != &o) {
    release();
    path_ = std::move(o.path_);
    data_ = std::exchange(o.data_, nullptr);
    size_ = o.size_;
    owner_ = std::exchange(o.owner_, false);
    lock_fd_ = std::exchange(o.lock_fd_, -1);
  }
  return *this;
}

namespace {

/// Whether `rest` (a file name after its lane prefix PATH.) is a ring's: <domain>.bell or
/// <domain>.from.<partner>, maybe with .tmp<pid> or .orphan<pid> after it.
bool ring_name(std::string rest) {
  for (const std::string mark : {".tmp", ".orphan"}) {
    const auto at = rest.rfind(mark);
    if (at != std::string::npos && at + mark.size() < rest.size() &&
        rest.find_first_not_of("0123456789", at + mark.size()) == std::string::npos)
      rest.resize(at);
  }
  const std::string bell = ".bell";
  if (rest.size() > bell.size() && rest.compare(rest.size() - bell.size(), bell.size(), bell) == 0)
    return rest.find('.') == rest.size() - bell.size();
  const auto from = rest.find(".from.");
  return from != std::string::npos && from > 0 && from + 6 < rest.size() &&
         rest.find('.', from + 6) == std::string::npos && rest.find('.') == from;
}

}  // namespace

std::size_t reclaim_orphan_shm_files(const std::string& dir, const std::string& prefix,
                                     bool ring_names_only) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !e.is_regular_file(ec)) continue;
    if (ring_names_only && !ring_name(name.substr(prefix.size()))) continue;
    // PATH.tmp<pid> (being written by <pid>) and PATH.orphan<pid> (being removed by <pid>): the
    // pid's own business while it lives
    const auto tmp = name.rfind(".tmp"), moving = name.rfind(".orphan");
    const auto mark = tmp != std::string::npos      ? tmp + 4
                      : moving != std::string::npos ? moving + 7
                                                    : tmp;
    if (mark != std::string::npos) {
      const std::string digits = name.substr(mark);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
      const auto pid = static_cast<pid_t>(std::stol(digits));
      if (::kill(pid, 0) == 0 || errno != ESRCH) continue;
    } else {
      const int fd = ::open(e.path().c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) continue;
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        // Nobody holds it. Move the name aside first (atomic) and remove it only if it is the
        // file we locked: a live run publishing under the same name meanwhile (a rename over it)
        // gets its file back at once.
        const std::string aside = fmt::format("{}.orphan{}", e.path().string(), ::getpid());
        struct stat locked {
        }, moved{};
        if (::fstat(fd, &locked) == 0 && ::rename(e.path().c_str(), aside.c_str()) == 0) {
          if (::stat(aside.c_str(), &moved) == 0 && moved.st_ino == locked.st_ino &&
              moved.st_dev == locked.st_dev) {
            ::unlink(aside.c_str());
            ++removed;
          } else {
            ::rename(aside.c_str(), e.path().c_str());
          }
        }
      }
      ::close(fd);
      continue;
    }
    if (std::filesystem::remove(e.path(), ec)) ++removed;
  }
  return removed;
}

namespace {

/// The creator's last step: the complete file takes its name.
void publish(const ShmMapping& m) {
  const std::string tmp = fmt::format("{}.tmp{}", m.path(), ::getpid());
  std::error_code ec;
  std::filesystem::rename(tmp, m.path(), ec);
  if (ec) {
    throw TransportError("shm://" + m.path(),
                         fmt::format("cannot rename {} to {}: {}", tmp, m.path(), ec.message()));
  }
}

/// The size of a complete file at `path` with `magic` in its first 8 bytes, or 0.
std::size_t complete_size(const std::string& path, std::uint64_t magic) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  std::uint64_t head[2] = {0, 0};
  const auto n = ::pread(fd, head, sizeof head, 0);
  ::close(fd);
  if (n != static_cast<ssize_t>(sizeof head) || head[0] != magic) return 0;
  return static_cast<std::size_t>(head[1]);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
struct ShmDoorbell::Header {
  std::uint64_t magic;
  std::uint64_t bytes;  // the file's size
  alignas(64) std::atomic<std::uint32_t> count;
  alignas(64) std::atomic<std::uint32_t> sleeping;
};
static_assert(sizeof(std::atomic<std::uint32_t>) == 4);

ShmDoorbell ShmDoorbell::create(const std::string& path) {
  ShmMapping m(path, kHeaderBytes, true);
  auto* h = new (m.data()) Header{};
  h->count.store(0);
  h->sleeping.store(0);
  h->bytes = kHeaderBytes;
  h->magic = kBellMagic;
  publish(m);
  return ShmDoorbell(std::move(m));
}

std::optional<ShmDoorbell> ShmDoorbell::open(const std::string& path) {
  const std::size_t bytes = complete_size(path, kBellMagic);
  if (bytes != kHeaderBytes) return std::nullopt;
  return ShmDoorbell(ShmMapping(path, bytes, false));
}

void ShmDoorbell::ring() {
  h().count.fetch_add(1, std::memory_order_seq_cst);
  if (h().sleeping.load(std::memory_order_seq_cst) != 0) futex(&h().count, FUTEX_WAKE, 1, nullptr);
}

std::uint32_t ShmDoorbell::count() const {
  return h().count.load(std::memory_order_seq_cst);
}

void ShmDoorbell::sleep(std::uint32_t seen, std::chrono::microseconds timeout) {
  const auto us = timeout.count();
  const timespec ts{static_cast<time_t>(us / 1000000), static_cast<long>((us % 1000000) * 1000)};
  h().sleeping.store(1, std::memory_order_seq_cst);
  futex(&h().count, FUTEX_WAIT, seen, &ts);  // returns at once if count != seen
  h().sleeping.store(0, std::memory_order_seq_cst);
}

// ---------------------------------------------------------------------------------------------
struct ShmQueue::Header {
  std::uint64_t magic;
  std::uint64_t bytes;                            // the file's size: header + ring
  std::uint64_t capacity;                         // ring bytes, a power of two
  alignas(64) std::atomic<std::uint64_t> head;    // bytes written, ever (sender)
  alignas(64) std::atomic<std::uint64_t> tail;    // bytes read, ever (receiver)
  alignas(64) std::atomic<std::uint32_t> opened;  // 1 once the sender has mapped the file
};

ShmQueue ShmQueue::create(const std::string& path, std::size_t capacity) {
  if (capacity < 4096 || (capacity & (capacity - 1)) != 0) {
    throw TransportError("shm://" + path,
                         fmt::format("ring capacity {} is not a power of two >= 4096", capacity));
  }
  static_assert(sizeof(Header) <= kHeaderBytes);
  ShmMapping m(path, kHeaderBytes + capacity, true);
  auto* h = new (m.data()) Header{};
  h->head.store(0);
  h->tail.store(0);
  h->opened.store(0);
  h->capacity = capacity;
  h->bytes = kHeaderBytes + capacity;
  h->magic = kQueueMagic;
  publish(m);
  return ShmQueue(std::move(m));
}

std::optional<ShmQueue> ShmQueue::open(const std::string& path) {
  const std::size_t bytes = complete_size(path, kQueueMagic);
  if (bytes <= kHeaderBytes) return std::nullopt;
  ShmQueue q(ShmMapping(path, bytes, false));
  q.h().opened.store(1, std::memory_order_seq_cst);
  return q;
}

bool ShmQueue::opened_by_sender() const {
  return h().opened.load(std::memory_order_seq_cst) != 0;
}

unsigned char* ShmQueue::ring() const {
  return static_cast<unsigned char*>(map_.data()) + kHeaderBytes;
}

void ShmQueue::copy_in(std::uint64_t at, const void* src, std::size_t n) {
  const std::size_t cap = h().capacity;
  const std::size_t off = static_cast<std::size_t>(at & (cap - 1));
  const std::size_t first = std::min(n, cap - off);
  std::memcpy(ring() + off, src, first);
  std::memcpy(ring(), static_cast<const unsigned char*>(src) + first, n - first);
}

void ShmQueue::copy_out(std::uint64_t at, void* dst, std::size_t n) const {
  const std::size_t cap = h().capacity;
  const std::size_t off = static_cast<std::size_t>(at & (cap - 1));
  const std::size_t first = std::min(n, cap - off);
  std::memcpy(dst, ring() + off, first);
  std::memcpy(static_cast<unsigned char*>(dst) + first, ring(), n - first);
}

void ShmQueue::push(std::string_view bytes, std::chrono::milliseconds timeout) {
  const std::uint64_t need = sizeof(std::uint64_t) + bytes.size();
  const std::uint64_t cap = h().capacity;
  if (need > cap) {
    throw TransportError("shm://" + path(),
                         fmt::format("a message of {} bytes does not fit the lane's ring of {} "
                                     "bytes; run with --no-lanes",
                                     bytes.size(), cap));
  }
  const std::uint64_t head = h().head.load(std::memory_order_relaxed);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (cap - (head - h().tail.load(std::memory_order_acquire)) < need) {
    if (std::chrono::steady_clock::now() >= deadline) {
      throw TransportError(
          "shm://" + path(),
          fmt::format("the receiver has not read its lane for {} ms ({} of {} "
                      "bytes in use)",
                      timeout.count(), head - h().tail.load(std::memory_order_acquire), cap));
    }
    std::this_thread::sleep_for(std::chrono::microseconds{50});
  }
  const std::uint64_t n = bytes.size();
  copy_in(head, &n, sizeof n);
  copy_in(head + sizeof n, bytes.data(), bytes.size());
  h().head.store(head + need, std::memory_order_seq_cst);
}

bool ShmQueue::empty() const {
  return h().head.load(std::memory_order_acquire) == h().tail.load(std::memory_order_relaxed);
}

std::optional<std::string> ShmQueue::pop() {
  std::string out;
  if (!pop_into(out)) return std::nullopt;
  return out;
}

bool ShmQueue::pop_into(std::string& out) {
  const std::uint64_t tail = h().tail.load(std::memory_order_relaxed);
  const std::uint64_t head = h().head.load(std::memory_order_acquire);
  if (head == tail) return false;
  std::uint64_t n = 0;
  copy_out(tail, &n, sizeof n);
  if (n > head - tail - sizeof n) {
    throw TransportError("shm://" + path(),
                         fmt::format("corrupt lane: a message of {} bytes announced with {} "
                                     "bytes written",
                                     n, head - tail - sizeof n));
  }
  out.resize(static_cast<std::size_t>(n));
  copy_out(tail + sizeof n, out.data(), out.size());
  h().tail.store(tail + sizeof n + n, std::memory_order_release);
  return true;
}

}  // namespace crashlink::transport
