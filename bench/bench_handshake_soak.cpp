// Handshake soak: 10^6 handshakes with flat memory (docs/processes.md "Soak"; the figures:
// docs/benchmarks.md "Handshake soak"). One long-lived coordinator endpoint (the product's
// CoordinatorLink, on its own thread) and N daemon connections made one after the other, each a
// new DaemonLink; the handshakes, what is printed and the verdict: soak.
// Exit 0 flat, 1 grows, 2 a handshake failed, a connection was not released, or bad arguments.
#include <fmt/format.h>
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "transport/coordinator_link.h"
#include "transport/daemon_link.h"
#include "transport/endpoint.h"
#include "transport/errors.h"

namespace {

using namespace std::chrono_literals;
namespace transport = crashlink::transport;
namespace wire = crashlink::wire;
using Clock = std::chrono::steady_clock;

constexpr std::string_view kHash = "soak-scenario";

struct Args {
  std::uint64_t handshakes = 1'000'000;
  std::uint64_t base = 10'000;  // the verdict compares RSS at N with RSS here
  std::uint64_t refuse_every = 10;
  int domains = 1;
  transport::Scheme scheme = transport::Scheme::ipc;
  double max_growth_kib = 1024;
  std::size_t leak_bytes = 0;
  std::uint64_t every = 0;  // also print every this many handshakes (0: no)
};

[[noreturn]] void usage(const std::string& why) {
  fmt::print(stderr,
             "bench_handshake_soak: {}\n"
             "usage: bench_handshake_soak [--handshakes N (1000000)] [--base B (10000)]\n"
             "         [--refuse-every K (10; 0: none)] [--domains D (1)]\n"
             "         [--transport ipc|tcp|inproc (ipc)] [--max-growth-kib G (1024)]\n"
             "         [--every E (0: only at 10^k)] [--leak-bytes L (0; self-check)]\n",
             why);
  std::exit(2);
}

std::uint64_t to_count(std::string_view flag, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);  // accepts 1e6
  if (end == text || *end != '\0' || v < 0 || v > 1e12) {
    usage(fmt::format("{} {}: need a count", flag, text));
  }
  return static_cast<std::uint64_t>(v);
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];
    if (i + 1 >= argc) usage(fmt::format("{} needs a value", flag));
    const char* value = argv[++i];
    if (flag == "--handshakes") {
      a.handshakes = to_count(flag, value);
    } else if (flag == "--base") {
      a.base = to_count(flag, value);
    } else if (flag == "--refuse-every") {
      a.refuse_every = to_count(flag, value);
    } else if (flag == "--domains") {
      a.domains = static_cast<int>(to_count(flag, value));
    } else if (flag == "--max-growth-kib") {
      a.max_growth_kib = static_cast<double>(to_count(flag, value));
    } else if (flag == "--every") {
      a.every = to_count(flag, value);
    } else if (flag == "--leak-bytes") {
      a.leak_bytes = to_count(flag, value);
    } else if (flag == "--transport") {
      const std::string_view s = value;
      if (s == "ipc") {
        a.scheme = transport::Scheme::ipc;
      } else if (s == "tcp") {
        a.scheme = transport::Scheme::tcp;
      } else if (s == "inproc") {
        a.scheme = transport::Scheme::inproc;
      } else {
        usage(fmt::format("--transport {}: ipc, tcp or inproc", s));
      }
    } else {
      usage(fmt::format("unknown option {}", flag));
    }
  }
  if (a.handshakes == 0 || a.domains < 1 || a.domains > 1000) usage("need N >= 1, 1 <= D <= 1000");
  if (a.base == 0 || a.base >= a.handshakes) usage("need 0 < base < N");
  return a;
}

struct Memory {
  double rss_kib = 0;
  double hwm_kib = 0;
  double anon_kib = 0;  // the part of RSS that is not file-backed (code, libraries)
  double heap_kib = 0;  // bytes handed out by malloc and not freed, all arenas
};

Memory memory() {
  Memory m;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) m.rss_kib = std::strtod(line.c_str() + 6, nullptr);
    if (line.rfind("VmHWM:", 0) == 0) m.hwm_kib = std::strtod(line.c_str() + 6, nullptr);
    if (line.rfind("RssAnon:", 0) == 0) m.anon_kib = std::strtod(line.c_str() + 8, nullptr);
  }
  m.heap_kib = static_cast<double>(mallinfo2().uordblks) / 1024.0;
  return m;
}

/// The coordinator's side: polls the link as a coordinator does, counts the Byes (the main thread
/// waits for each before the next daemon reuses its routing id) and the notices.
class Coordinator {
 public:
  explicit Coordinator(transport::CoordinatorLink& link) : link_(link) {
    thread_ = std::thread([this] { run(); });
  }
  ~Coordinator() {
    stop_ = true;
    thread_.join();
  }
  Coordinator(const Coordinator&) = delete;
  Coordinator& operator=(const Coordinator&) = delete;

  /// Waits until the coordinator has seen `n` Byes; false after `timeout`.
  bool await_byes(std::uint64_t n, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return seen_.wait_for(lock, timeout, [&] { return byes_ >= n; });
  }
  std::uint64_t refusal_notices() const { return refusal_notices_; }
  std::uint64_t other_notices() const { return other_notices_; }
  std::uint64_t unexpected() const { return unexpected_; }
  std::string first_other() {
    std::lock_guard lock(mutex_);
    return first_other_;
  }

 private:
  void run() {
    while (!stop_) {
      try {
        auto in = link_.poll(20ms);
        for (const auto& n : link_.take_notices()) {
          if (n.text.rfind("refused Hello", 0) == 0) {
            ++refusal_notices_;
          } else if (other_notices_++ == 0) {
            std::lock_guard lock(mutex_);
            first_other_ = n.text;
          }
        }
        if (!in) continue;
        if (in->envelope.has_bye()) {
          {
            std::lock_guard lock(mutex_);
            ++byes_;
          }
          seen_.notify_one();
        } else {
          ++unexpected_;
        }
      } catch (const std::exception& e) {
        fmt::print(stderr, "coordinator: {}\n", e.what());
        ++unexpected_;
      }
    }
  }

  transport::CoordinatorLink& link_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable seen_;
  std::uint64_t byes_ = 0;
  std::atomic<std::uint64_t> refusal_notices_{0};
  std::atomic<std::uint64_t> other_notices_{0};
  std::atomic<std::uint64_t> unexpected_{0};
  std::string first_other_;  // guarded by mutex_
};

/// Open file descriptors of this process (sockets, eventfds, the listener, ...).
int open_fds() {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
  return n;
}

/// --leak-bytes B leaks B bytes per handshake on purpose (a self-check: the verdict must say
/// GROWS; ctest Soak.HandshakesShortCatchesALeak): blocks chained through their first bytes (no
/// container that would grow too), written so that they are resident.
void* leak(std::size_t bytes, void* previous) {
  if (bytes == 0) return previous;
  auto* block = static_cast<unsigned char*>(std::malloc(std::max(bytes, sizeof(void*))));
  std::memset(block, 0x5a, std::max(bytes, sizeof(void*)));
  std::memcpy(block, static_cast<void*>(&previous), sizeof(void*));
  return block;
}

/// The coordinator endpoint is polled on its own thread as the coordinator polls it (Coordinator);
/// the main thread makes N daemon connections one after the other, each a new DaemonLink (new
/// DEALER socket, new tcp/ipc connection): Hello -> the coordinator's Hello -> Bye -> close.
/// Every --refuse-every'th daemon carries a wrong scenario hash and is refused with an Error
/// (ERROR_CODE_SCENARIO_MISMATCH), so the refusal path is soaked too. The domains are the
/// coordinator's configured ones (--domains, used in turn), as in a run: the soak reuses routing
/// ids, which is what a long-lived ROUTER must survive without keeping per-connection state.
/// Before the next handshake it waits until both ends of the last connection are closed (ZeroMQ
/// closes them in background threads; without the wait they pile up by the hundred).
/// At 10^3, 10^4, ... and at N it prints the resident memory (VmRSS), its peak (VmHWM), its
/// anonymous part (RssAnon), the heap in use (glibc mallinfo2: every arena, every thread), the
/// rate and the refusals; the last line is the verdict: RSS and heap at N against at --base
/// (after the warm-up), flat when both grew less than --max-growth-kib. Returns the exit code.
int soak(const Args& args) {
  std::vector<std::string> domains;
  for (int d = 0; d < args.domains; ++d) domains.push_back(fmt::format("soak{}", d));
  transport::SessionOptions options;
  options.handshake_timeout = 10s;
  transport::CoordinatorLink link(transport::local_endpoint(args.scheme, "soak"),
                                  {std::string(kHash), domains, 1'000'000'000, options});
  Coordinator coordinator(link);

  // 10^3, 10^4, ... below N, the base and N.
  std::vector<std::uint64_t> checkpoints = {args.base, args.handshakes};
  for (std::uint64_t c = 1000; c < args.handshakes; c *= 10) checkpoints.push_back(c);
  for (std::uint64_t c = args.every; c > 0 && c < args.handshakes; c += args.every) {
    checkpoints.push_back(c);
  }
  std::sort(checkpoints.begin(), checkpoints.end());
  checkpoints.erase(std::unique(checkpoints.begin(), checkpoints.end()), checkpoints.end());

  fmt::print(
      "handshake soak: {} handshakes over {}, one coordinator ({}), domains {}, 1 in {} "
      "refused (wrong scenario hash){}\n",
      args.handshakes, transport::scheme_name(args.scheme), link.endpoint(), args.domains,
      args.refuse_every,
      args.leak_bytes > 0 ? fmt::format(", LEAKING {} B per handshake on purpose", args.leak_bytes)
                          : "");
  fmt::print("{:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>9} {:>8}\n", "handshakes", "RSS_KiB",
             "HWM_KiB", "anon_KiB", "heap_KiB", "per_s", "refused", "t_s");
  std::fflush(stdout);

  // ZeroMQ closes a connection in the background (reaper and I/O threads). Before the next
  // handshake the bench waits until both ends of the last one are closed (open fds back to what
  // they were with the coordinator alone): no teardown backlog (it would raise the peak, and at
  // ~1000 connections hit the fd limit), and a connection that is never released fails the soak.
  const int idle_fds = open_fds();
  double max_drain_ms = 0;
  const auto start = Clock::now();
  auto last_time = start;
  std::uint64_t last_count = 0;
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;
  void* leaked = nullptr;
  Memory at_base;
  Memory at_end;
  std::size_t next = 0;
  for (std::uint64_t i = 1; i <= args.handshakes; ++i) {
    const std::string& domain = domains[i % domains.size()];
    const bool refuse = args.refuse_every > 0 && i % args.refuse_every == 0;
    try {
      transport::DaemonLink daemon(
          link.endpoint(), transport::daemon_hello(domain, refuse ? "another-scenario" : kHash),
          options);
      if (refuse) throw std::runtime_error("a Hello with the wrong scenario hash was accepted");
      if (daemon.coordinator_hello().scenario_hash() != kHash) {
        throw std::runtime_error("the coordinator's Hello has another scenario hash");
      }
      daemon.bye("soak");
      ++accepted;
    } catch (const transport::RemoteError& e) {
      if (!refuse || e.code() != wire::ERROR_CODE_SCENARIO_MISMATCH) {
        fmt::print(stderr, "handshake {} ({}): refused: {}\n", i, domain, e.what());
        return 2;
      }
      ++refused;
    } catch (const std::exception& e) {
      fmt::print(stderr, "handshake {} ({}): {}\n", i, domain, e.what());
      return 2;
    }
    // The next daemon with this routing id must find this session ended: wait for its Bye.
    if (!refuse && !coordinator.await_byes(accepted, 10s)) {
      fmt::print(stderr, "handshake {} ({}): the coordinator did not see the Bye within 10 s\n", i,
                 domain);
      return 2;
    }
    const auto closing = Clock::now();
    while (open_fds() > idle_fds) {
      if (Clock::now() - closing > 10s) {
        fmt::print(stderr,
                   "handshake {} ({}): {} fds open 10 s after it, {} before: a connection "
                   "is not released\n",
                   i, domain, open_fds(), idle_fds);
        return 2;
      }
      std::this_thread::sleep_for(50us);
    }
    max_drain_ms = std::max(
        max_drain_ms, std::chrono::duration<double, std::milli>(Clock::now() - closing).count());
    leaked = leak(args.leak_bytes, leaked);
    if (i != checkpoints[next]) continue;
    ++next;
    const auto now = Clock::now();
    const Memory m = memory();
    if (i == args.base) at_base = m;
    if (i == args.handshakes) at_end = m;
    const double dt = std::chrono::duration<double>(now - last_time).count();
    fmt::print("{:>10} {:>10.0f} {:>10.0f} {:>10.0f} {:>10.0f} {:>10.0f} {:>9} {:>8.1f}\n", i,
               m.rss_kib, m.hwm_kib, m.anon_kib, m.heap_kib,
               static_cast<double>(i - last_count) / dt, refused,
               std::chrono::duration<double>(now - start).count());
    std::fflush(stdout);
    last_time = now;
    last_count = i;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  // The coordinator thread takes the last notices after its next poll (<= 20 ms).
  for (int k = 0; k < 100 && coordinator.refusal_notices() < refused; ++k) {
    std::this_thread::sleep_for(20ms);
  }
  fmt::print(
      "{} handshakes in {:.1f} s ({:.0f}/s): {} accepted, {} refused; coordinator notices: "
      "{} refused Hellos, {} others{}{}; teardown wait at most {:.1f} ms\n",
      args.handshakes, seconds, static_cast<double>(args.handshakes) / seconds, accepted, refused,
      coordinator.refusal_notices(), coordinator.other_notices(),
      coordinator.other_notices() > 0 ? " (first: " + coordinator.first_other() + ")" : "",
      link.dropped_notices() > 0 ? fmt::format(", {} dropped", link.dropped_notices()) : "",
      max_drain_ms);
  if (coordinator.refusal_notices() != refused || coordinator.unexpected() > 0 ||
      coordinator.other_notices() > 0) {
    fmt::print(stderr, "the coordinator saw something else than the handshakes and Byes\n");
    return 2;
  }
  const double growth = at_end.rss_kib - at_base.rss_kib;
  const double heap_growth = at_end.heap_kib - at_base.heap_kib;
  const double span = static_cast<double>(args.handshakes - args.base);
  const bool flat = growth < args.max_growth_kib && heap_growth < args.max_growth_kib;
  fmt::print(
      "verdict: {}: RSS {:+.0f} KiB and heap {:+.0f} KiB from {} to {} handshakes "
      "(limit {:.0f} KiB: a leak of {:.1f} B per handshake or more would cross it)\n",
      flat ? "FLAT" : "GROWS", growth, heap_growth, args.base, args.handshakes, args.max_growth_kib,
      args.max_growth_kib * 1024.0 / span);
  return flat ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return soak(parse(argc, argv));
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_handshake_soak: {}\n", e.what());
    return 2;
  }
}
