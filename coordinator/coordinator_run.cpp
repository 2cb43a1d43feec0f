#include "coordinator/coordinator_run.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <utility>

#include "coordinator/admission.h"
#include "coordinator/coordinator_checkpoints.h"
#include "coordinator/coordinator_schemes.h"
#include "coordinator/coordinator_stops.h"
#include "coordinator/coupling_history.h"
#include "coordinator/session_files.h"
#include "core/cpu_clock.h"
#include "core/errors.h"
#include "core/exit_codes.h"
#include "core/log_escape.h"
#include "coupling/interface_match.h"
#include "coupling/stall_watch.h"
#include "proto/envelope_name.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "solver/run/checkpoint_store.h"
#include "transport/coordinator_link.h"
#include "transport/errors.h"
#include "transport/failure.h"
#include "transport/shm_lane.h"

namespace crashlink::coordinator {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

class Coordinator final : private CoordinatorPort {
 public:
  explicit Coordinator(const CoordinatorOptions& o) : o_(o) {}

  CoordinatorResult run() {
    wall0_ = Clock::now();
    cpu0_ = clock_cpu_seconds();
    std::optional<Stop> stop;
    try {
      prepare();
      admit();
      route();
      checkpoints_->prune_all();
    } catch (const StopRun& s) {
      stop = s.stop();
    } catch (const transport::PeerTimeoutError& e) {
      stop = Stop{kExitPeer, wire::ERROR_CODE_TIMEOUT,
                  link_ ? link_->dead_peers() : std::vector<std::string>{},
                  fmt::format("coordinator: {}", e.what())};
    } catch (...) {
      const auto f = transport::current_failure();
      stop = Stop{f.exit_code, f.code, {}, fmt::format("coordinator: {}", f.text)};
    }
    CoordinatorResult r;
    if (stop) {
      tell_everyone(*stop);
      r.exit_code = stop->exit_code;
      r.message = stop->text;
      r.culprit = stop->culprits.empty() ? std::string() : stop->culprits.front();
    }
    // Only what this coordinator made: another one may be running on that socket or file.
    remove_session_files(link_ ? o_.bind : std::string(),
                         endpoint_written_ ? o_.endpoint_file : std::string(),
                         admission_ ? admission_->lane_endpoints() : std::vector<std::string>{},
                         scheme_ ? cut().names : std::vector<std::string>{});
    r.cpu_seconds = run_cpu_seconds();
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0_).count();
    close_history(r);
    r.endpoint = link_ ? link_->endpoint() : std::string();
    r.notices = notices_;
    if (scheme_) scheme_->fill_result(r);
    if (checkpoints_) {
      r.checkpoint_interval_ticks = checkpoints_->every();
      r.restarted_from_ticks = checkpoints_->restarted_from();
    }
    r.domains = outcomes_;
    return r;
  }

 private:
  double clock_cpu_seconds() const { return core::cpu_seconds(o_.in_process); }
  /// CPU of this run, plus that of the run(s) before the checkpoint it restarted from.
  double run_cpu_seconds() const {
    return (scheme_ ? scheme_->cpu_before() : 0.0) + clock_cpu_seconds() - cpu0_;
  }

  // CoordinatorPort: what the scheme may ask.
  /// A Setup leaves with this run's scheme name (Setup.scheme), whatever the scheme filled in.
  void send(int k, const wire::Envelope& e) override {
    const auto& to = cut().names[static_cast<std::size_t>(k)];
    if (e.has_setup() && e.setup().scheme() != o_.run.scheme) {
      wire::Envelope named = e;
      named.mutable_setup()->set_scheme(o_.run.scheme);
      link_->send(to, named);
      return;
    }
    link_->send(to, e);
  }
  /// The message's bytes as they came (CoordinatorLink::forward: no re-serialisation, no copy).
  void forward_current(int to) override {
    if (current_ == nullptr)
      throw std::logic_error("CoordinatorPort::forward_current outside the handling of a message");
    if (outcomes_[static_cast<std::size_t>(to)].finished) return;  // nothing left to use it for
    link_->forward(cut().names[static_cast<std::size_t>(to)], *current_);
  }
  /// 10 peer timeouts and at least 30 s (CoordinatorLink::allow_silence).
  void allow_silence(int k) override {
    link_->allow_silence(cut().names[static_cast<std::size_t>(k)],
                         std::max<std::chrono::milliseconds>(10 * o_.session.peer_timeout,
                                                             std::chrono::seconds{30}));
  }
  CouplingHistory& history() override { return *history_; }
  CoordinatorCheckpoints& checkpoints() override { return *checkpoints_; }
  double cpu_seconds() const override { return run_cpu_seconds(); }
  void log(const std::string& line) override {
    if (o_.log == nullptr) return;
    std::fprintf(o_.log, "crashlink-coordinator: %s\n", line.c_str());
    std::fflush(o_.log);
  }

  const LayerCut& cut() const { return scheme_->cut(); }

  void prepare() {
    validate(o_.run);  // every rule on the configuration (coordinator_schemes.h)
    auto read = io::read_scenario_with_hash(o_.scenario);  // one parse for both
    const std::string hash = std::move(read.hash);
    model_ = std::make_unique<model::Model>(std::move(read.model));
    scheme_ = coordinator_scheme_named(o_.run.scheme).make(*model_, o_);
    const auto& names = cut().names;
    outcomes_.resize(names.size());
    for (std::size_t k = 0; k < names.size(); ++k) outcomes_[k].name = names[k];
    latest_.assign(names.size(), 0);

    std::filesystem::create_directories(o_.out_dir);
    if (!o_.run.restart) run::remove_checkpoints(o_.out_dir, run::kCoordinatorPiece);
    checkpoints_ = std::make_unique<CoordinatorCheckpoints>(o_, cut(), hash);
    history_ = std::make_unique<CouplingHistory>(
        (std::filesystem::path(o_.out_dir) / "coordinator.h5").string(), cut(), o_.run.scheme);

    transport::CoordinatorConfig config;
    config.scenario_hash = hash;
    config.domains = cut().names;
    config.ticks_per_second = o_.run.ticks_per_second;
    config.options = o_.session;
    link_ = std::make_unique<transport::CoordinatorLink>(o_.bind, config);
    reclaim_orphan_lanes(o_.bind, o_.log);
    if (!o_.endpoint_file.empty()) {
      write_file_atomically(o_.endpoint_file, link_->endpoint() + "\n");
      endpoint_written_ = true;
    }
    if (o_.log != nullptr) {
      std::fprintf(o_.log, "crashlink-coordinator: listening on %s for %zu domains ('%s')\n",
                   link_->endpoint().c_str(), cut().names.size(),
                   fmt::format("{}", fmt::join(cut().names, "', '")).c_str());
      std::fflush(o_.log);
    }
    if (o_.on_bound) o_.on_bound(link_->endpoint());
  }

  int index_of(const std::string& domain) const {
    const auto it = std::find(cut().names.begin(), cut().names.end(), domain);
    return it == cut().names.end() ? -1 : static_cast<int>(it - cut().names.begin());
  }

  /// Every domain joins and registers (admission.h); then the Setups.
  void admit() {
    admission_ = std::make_unique<Admission>(o_, *scheme_, *link_);
    admission_->run([this] { check_stop_requested(); }, [this] { log_notices(); });
    wire::Options options;
    options.set_heartbeat_interval_ms(
        static_cast<std::uint32_t>(o_.session.heartbeat_interval.count()));
    options.set_peer_timeout_ms(static_cast<std::uint32_t>(o_.session.peer_timeout.count()));
    try {
      scheme_->start(admission_->registers(), options, *this);
    } catch (const coupling::InterfaceError& x) {
      throw StopRun(Stop{kExitInput, wire::ERROR_CODE_MODEL, x.domains(),
                         fmt::format("coordinator: {}", x.what())});
    }
    for (std::size_t k = 0; k < cut().names.size(); ++k) {
      outcomes_[k].step_ticks = scheme_->step(static_cast<int>(k));
      latest_[k] = scheme_->reached(static_cast<int>(k));
    }
  }

  void route() {
    std::size_t done = 0;
    const double end_s = cut().end_time_s;
    coupling::StallWatch stall(2 * o_.session.peer_timeout);
    while (done < cut().names.size()) {
      check_stop_requested();
      auto in = link_->poll(100ms);
      log_notices();
      if (in) {
        const int k = index_of(in->domain);
        auto& e = in->envelope;
        // forward_current() reaches this message only while it is handled.
        struct ClearOnExit {
          transport::Incoming*& slot;
          ~ClearOnExit() { slot = nullptr; }
        };
        current_ = &*in;
        const ClearOnExit clear{current_};
        try {
          if (scheme_->receive(k, e, *this)) {
            latest_[static_cast<std::size_t>(k)] = scheme_->reached(k);
          } else if (e.has_bye()) {
            scheme_->bye(k, e.bye(), *this);
            bye(k, e.bye());
            ++done;
          } else if (e.has_error()) {
            throw StopRun(remote_error_stop(in->domain, e.error()));
          } else {
            throw StopRun(
                protocol_stop(in->domain, fmt::format("domain '{}' sent a {} during the run",
                                                      in->domain, wire::body_name(e))));
          }
        } catch (const ProtocolError& x) {
          throw StopRun(protocol_stop(in->domain, x.what()));
        }
        if (o_.on_progress) {
          const int slow = slowest();
          const double t = slow < 0 ? end_s
                                    : static_cast<double>(latest_[static_cast<std::size_t>(slow)]) /
                                          static_cast<double>(o_.run.ticks_per_second);
          o_.on_progress(t, end_s,
                         slow < 0 ? std::string() : cut().names[static_cast<std::size_t>(slow)]);
        }
      }
      link_->check_alive();
      if (stall.stuck(latest_, done, coupling::StallWatch::Clock::now())) {
        std::vector<bool> finished;
        for (const auto& out : outcomes_) finished.push_back(out.finished);
        throw StopRun(
            stuck_stop(cut().names, finished, latest_, o_.run.ticks_per_second, stall.still_for()));
      }
    }
  }

  /// The unfinished domain furthest behind (by its latest report), or -1.
  int slowest() const {
    int slow = -1;
    for (std::size_t k = 0; k < cut().names.size(); ++k) {
      if (outcomes_[k].finished) continue;
      const int ki = static_cast<int>(k);
      if (slow < 0 || latest_[k] < latest_[static_cast<std::size_t>(slow)]) slow = ki;
    }
    return slow;
  }

  void bye(int k, const wire::Bye& b) {
    auto& out = outcomes_[static_cast<std::size_t>(k)];
    out.finished = true;
    const auto& r = b.report();
    out.cpu_seconds = r.cpu_seconds();
    out.wait_seconds = r.wait_seconds();
    out.wall_seconds = r.wall_seconds();
    out.cycles = r.cycles();
    out.dt_min_s = r.dt_min_s();
    out.elements = r.elements();
  }

  void check_stop_requested() const {
    if (o_.stop != nullptr && o_.stop->load()) throw StopRun(requested_stop());
  }

  void log_notices() {
    if (!link_) return;
    for (const auto& n : link_->take_notices()) {
      ++notices_;
      // A dead peer makes every heartbeat fail until the timeout: say it once.
      if (!logged_.insert(n.text).second) continue;
      if (o_.log != nullptr) {
        std::fprintf(o_.log, "crashlink-coordinator: notice: %s\n", n.text.c_str());
        std::fflush(o_.log);
      }
    }
  }

  /// The Error naming the culprit, to every daemon still in session (a domain that reported the
  /// Error itself has ended its session; a frozen one reads it when it wakes up).
  void tell_everyone(const Stop& s) {
    if (!link_) return;
    const std::string culprit = s.culprits.empty() ? std::string() : s.culprits.front();
    for (const auto& name : cut().names) {
      if (!link_->joined(name)) continue;
      try {
        link_->send(name, transport::make_error(s.code, s.text, culprit));
      } catch (const std::exception&) {
        // That daemon is gone too; its own timeout or exit tells.
      }
    }
  }

  void close_history(const CoordinatorResult& r) {
    if (!history_) return;
    try {
      history_->finish(r.wall_seconds, r.cpu_seconds, outcomes_);
    } catch (const std::exception& e) {
      if (o_.log != nullptr) {
        std::fprintf(o_.log, "crashlink-coordinator: writing %s failed: %s\n",
                     history_->path().c_str(), e.what());
      }
    }
  }

  const CoordinatorOptions& o_;
  Clock::time_point wall0_;
  double cpu0_ = 0.0;
  std::unique_ptr<model::Model> model_;
  std::unique_ptr<CoordinatorScheme> scheme_;
  std::unique_ptr<Admission> admission_;
  std::vector<DomainOutcome> outcomes_;
  std::unique_ptr<CouplingHistory> history_;
  std::unique_ptr<CoordinatorCheckpoints> checkpoints_;
  std::unique_ptr<transport::CoordinatorLink> link_;
  std::int64_t notices_ = 0;
  std::set<std::string> logged_;
  std::vector<coupling::Tick> latest_;      ///< [daemons] the instant of the latest report
  transport::Incoming* current_ = nullptr;  ///< the message being handled (forward_current)
  bool endpoint_written_ = false;           ///< the endpoint file is ours to remove
};

}  // namespace

CoordinatorResult run_coordinator(const CoordinatorOptions& options) {
  return Coordinator(options).run();
}

}  // namespace crashlink::coordinator
