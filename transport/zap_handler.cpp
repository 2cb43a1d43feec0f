#include "transport/zap_handler.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <iterator>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "transport/curve_key.h"
#include "transport/detail/zmq.h"

namespace crashlink::transport {

struct ZapDomain::State {
  std::string name;
  std::unordered_set<std::string> authorized;  ///< guarded by m once built
  bool pending = false;                        ///< keys to come (authorize); guarded by m
  bool later = false;                          ///< built to be authorized later (a lane)
  std::condition_variable ready;
  std::string keys_file;
  std::atomic<std::uint64_t> accepted{0};
  std::mutex m;
  std::vector<CurveRefusal> refusals;
};

namespace {

constexpr const char* kZapEndpoint = "inproc://zeromq.zap.01";
constexpr std::size_t kMaxRefusals = 1000;

/// The peer as a ZAP request names it: tcp "IP"; ipc "localhost:UID:GID:PID" (its credentials).
std::string peer_name(const std::string& address) {
  if (address.empty()) return "a local peer";
  unsigned uid = 0, gid = 0, pid = 0;
  char tail = 0;
  if (std::sscanf(address.c_str(), "localhost:%u:%u:%u%c", &uid, &gid, &pid, &tail) == 3) {
    return fmt::format("the local process {} (uid {}, gid {})", pid, uid, gid);
  }
  return address;
}

/// The one handler of the process. add() and remove() run on the Routers' threads, serve() on
/// the handler's own; `life_` orders starts and stops, `m_` guards the table of domains.
class Handler {
 public:
  static Handler& instance() {
    static Handler handler;  // after the context (constructed first, below): destroyed before it
    return handler;
  }

  std::string add(const std::shared_ptr<ZapDomain::State>& state) {
    std::lock_guard life(life_);
    if (!thread_.joinable()) start();
    std::lock_guard lock(m_);
    std::string name = fmt::format("crashlink-{}-{}", ::getpid(), ++next_);
    domains_[name] = state;
    return name;
  }

  void remove(const std::string& name) {
    std::lock_guard life(life_);
    bool last = false;
    {
      std::lock_guard lock(m_);
      domains_.erase(name);
      last = domains_.empty();
    }
    if (last) stop();
  }

  ~Handler() {
    std::lock_guard life(life_);
    if (thread_.joinable()) stop();
  }

 private:
  Handler() { (void)detail::process_context(); }

  /// Binds the ZAP endpoint here (so a failure throws to the Router being built), then hands the
  /// sockets to the thread (a thread start is a full memory barrier, which ZeroMQ asks for).
  void start() {
    auto& context = detail::process_context();
    zmq::socket_t rep(context, zmq::socket_type::rep);
    rep.set(zmq::sockopt::linger, 0);
    rep.bind(kZapEndpoint);
    const std::string wake_endpoint = fmt::format("inproc://crashlink-zap-wake-{}", ++wakes_);
    zmq::socket_t wake_in(context, zmq::socket_type::pair);
    wake_in.set(zmq::sockopt::linger, 0);
    wake_in.bind(wake_endpoint);
    wake_ = zmq::socket_t(context, zmq::socket_type::pair);
    wake_.set(zmq::sockopt::linger, 0);
    wake_.connect(wake_endpoint);
    thread_ = std::thread([this, r = std::move(rep), w = std::move(wake_in)]() mutable {
      serve(r, w);
      try {
        r.unbind(kZapEndpoint);  // synchronous for inproc: the next start can bind again
      } catch (const zmq::error_t&) {
      }
      r.close();
      w.close();
    });
  }

  void stop() {
    try {
      (void)wake_.send(zmq::str_buffer("stop"), zmq::send_flags::dontwait);
    } catch (const zmq::error_t&) {
    }
    thread_.join();
    wake_.close();
  }

  void serve(zmq::socket_t& rep, zmq::socket_t& wake) {
    std::vector<zmq::message_t> frames;
    for (;;) {
      zmq::pollitem_t items[] = {{rep.handle(), 0, ZMQ_POLLIN, 0},
                                 {wake.handle(), 0, ZMQ_POLLIN, 0}};
      try {
        // The timeout only bounds the wait; the wake socket ends it at once.
        (void)zmq::poll(items, 2, std::chrono::milliseconds{1000});
      } catch (const zmq::error_t& e) {
        if (e.num() == EINTR) continue;
        return;  // context terminated
      }
      if ((items[1].revents & ZMQ_POLLIN) != 0) return;
      if ((items[0].revents & ZMQ_POLLIN) == 0) continue;
      frames.clear();
      try {
        if (!zmq::recv_multipart(rep, std::back_inserter(frames), zmq::recv_flags::dontwait)) {
          continue;
        }
        reply(rep, frames);
      } catch (const zmq::error_t& e) {
        if (e.num() == ETERM) return;
      }
    }
  }

  /// Answers one ZAP request: version, request id, domain, address, identity, mechanism,
  /// credentials (CURVE: the client's 32-byte public key).
  void reply(zmq::socket_t& rep, const std::vector<zmq::message_t>& frames) {
    std::string id = frames.size() > 1 ? frames[1].to_string() : std::string();
    auto answer = [&](std::string_view code, std::string_view text, std::string_view user) {
      std::array<zmq::const_buffer, 6> out = {zmq::str_buffer("1.0"),
                                              zmq::buffer(id.data(), id.size()),
                                              zmq::buffer(code.data(), code.size()),
                                              zmq::buffer(text.data(), text.size()),
                                              zmq::buffer(user.data(), user.size()),
                                              zmq::const_buffer()};
      (void)zmq::send_multipart(rep, out);
    };
    if (frames.size() < 6 || frames[0].to_string_view() != "1.0") {
      answer("500", "malformed ZAP request", "");
      return;
    }
    const std::string domain = frames[2].to_string();
    const std::string address = frames[3].to_string();
    const std::string mechanism = frames[5].to_string();
    if (mechanism != "CURVE") {
      answer("200", "not a CURVE connection: not ours to check", "");
      return;
    }
    std::shared_ptr<ZapDomain::State> state;
    {
      std::lock_guard lock(m_);
      const auto it = domains_.find(domain);
      if (it != domains_.end()) state = it->second;
    }
    if (frames.size() < 7 || frames[6].size() != 32) {
      answer("400", "CURVE request without a 32-byte client key", "");
      return;
    }
    const std::string key = curve_key_text(frames[6].to_string_view());
    if (state == nullptr) {
      answer("400", "unknown ZAP domain", "");
      return;
    }
    bool known = false;
    std::size_t n_keys = 0;
    bool later = false;
    {
      // A lane's keys come with the coordinator's Setup, which its partner may have before it.
      std::unique_lock lock(state->m);
      later = state->later;
      state->ready.wait_for(lock, std::chrono::seconds{10}, [&] { return !state->pending; });
      known = state->authorized.contains(key);
      n_keys = state->authorized.size();
    }
    if (known) {
      ++state->accepted;
      answer("200", "OK", key);
      return;
    }
    CurveRefusal r;
    r.address = address;
    r.client_key = key;
    r.text = fmt::format(
        "refused a CURVE connection from {}: client public key {} is not in {} ({} keys); {}",
        peer_name(address), key,
        later ? state->keys_file : fmt::format("the authorized keys file {}", state->keys_file),
        n_keys,
        later ? "this lane takes only its partners' vectors: is another process connecting to it?"
              : "fix: if it is a daemon of this run, append its PREFIX.pub to that file and "
                "restart the coordinator");
    {
      // Recorded before the answer: once the client knows, the coordinator's log can say it.
      std::lock_guard lock(state->m);
      if (state->refusals.size() < kMaxRefusals) state->refusals.push_back(std::move(r));
    }
    answer("400", "client key not authorized", "");
  }

  std::mutex life_;
  std::mutex m_;
  std::unordered_map<std::string, std::shared_ptr<ZapDomain::State>> domains_;
  std::thread thread_;
  zmq::socket_t wake_;
  std::uint64_t next_ = 0;
  std::uint64_t wakes_ = 0;
};

}  // namespace

ZapDomain::ZapDomain(std::vector<std::string> authorized, std::string keys_file, bool later)
    : state_(std::make_shared<State>()) {
  state_->authorized.insert(authorized.begin(), authorized.end());
  state_->keys_file = std::move(keys_file);
  state_->pending = later;
  state_->later = later;
  state_->name = Handler::instance().add(state_);
}

void ZapDomain::authorize(std::vector<std::string> keys) {
  {
    std::lock_guard lock(state_->m);
    state_->authorized = {keys.begin(), keys.end()};
    state_->pending = false;
  }
  state_->ready.notify_all();
}

ZapDomain::~ZapDomain() {
  Handler::instance().remove(state_->name);
}

const std::string& ZapDomain::name() const {
  return state_->name;
}

std::vector<CurveRefusal> ZapDomain::take_refusals() {
  std::lock_guard lock(state_->m);
  return std::exchange(state_->refusals, {});
}

std::uint64_t ZapDomain::accepted() const {
  return state_->accepted.load();
}

}  // namespace crashlink::transport
