#include "solver/daemon/daemon.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "proto/envelope_name.h"
#include "solver/daemon/daemon_checkpoints.h"
#include "solver/daemon/daemon_failure.h"
#include "solver/daemon/daemon_handshake.h"
#include "solver/daemon/daemon_lanes.h"
#include "solver/daemon/domain_output.h"
#include "solver/daemon/domain_schemes.h"
#include "solver/io/result_writer.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "solver/run/checkpoint_store.h"
#include "solver/run/domain_checkpoint.h"
#include "solver/run/domain_recorder.h"
#include "transport/daemon_link.h"
#include "transport/dealer.h"
#include "transport/errors.h"
#include "transport/lane_endpoint.h"
#include "transport/router.h"
#include "transport/shm_lane.h"

namespace crashlink::daemon {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

class Daemon {
 public:
  explicit Daemon(const DaemonOptions& o) : o_(o) {}

  DaemonResult run() {
    wall0_ = Clock::now();
    cpu0_ = cpu_seconds();
    std::optional<DaemonFailure> failure;
    try {
      prepare();
      connect();
      loop();
      finish();
    } catch (...) {
      failure = current_daemon_failure(where());
    }
    DaemonResult r;
    if (failure) {
      if (failure->tell_coordinator)
        tell_coordinator(*failure, link_, o_.endpoint, o_.domain, hash_, o_.session);
      if (output_)
        output_->close_after_failure(seconds_since(wall0_), run_cpu_seconds(), elements_);
      r.exit_code = failure->exit_code;
      r.message = failure->text;
    }
    r.result_h5 = h5_path_;
    r.cycles = solver() ? solver()->cycle() : 0;
    r.cpu_seconds = run_cpu_seconds();
    r.wait_seconds = wait_s_;
    r.wall_seconds = seconds_since(wall0_);
    return r;
  }

 private:
  integration::Solver* solver() const { return scheme_ ? &scheme_->solver() : nullptr; }

  /// In process, this thread's clock plus the solver's worker threads' (their CPU since they
  /// started, after cpu0_ was read).
  double cpu_seconds() const {
    const double team = o_.in_process && solver() ? solver()->team_cpu_seconds() : 0.0;
    return core::cpu_seconds(o_.in_process) + team;
  }

  /// CPU of this run, plus that of the run(s) before the checkpoint it restarted from.
  double run_cpu_seconds() const { return cpu_before_ + cpu_seconds() - cpu0_; }

  /// docs/design.md §2.6 "Checkpoints": between two cycles at a multiple of the coordinator's
  /// interval, with every message up to this instant sent and consumed (the scheme's save_state).
  /// The result file's rows so far go along as a copy, so a restart rebuilds its file from it.
  void write_checkpoint() {
    const coupling::Tick T = scheme_->time();
    send_report(true);  // the interface history up to T, which the coordinator's checkpoint holds
    checkpoints_->write(T, seconds(T), output_->recorder(), *solver(), run_cpu_seconds(),
                        [this](core::StateWriter& w) {
                          w.put_double("run.wait_seconds", wait_s_);
                          scheme_->save_state(w);
                        });
  }

  /// Resumes from this domain's checkpoint at T (the coordinator's choice, from our Register).
  void restore(coupling::Tick T) {
    cpu_before_ = checkpoints_->restore(T, seconds(T), output_->recorder(), *solver(),
                                        [this](const core::StateReader& r) {
                                          scheme_->restore_state(r);
                                          wait_s_ = r.get_double("run.wait_seconds");
                                        });
  }

  /// What the scheme is built with: the domain, the step safety and cap of its proposals.
  coupling::DomainSchemeOptions scheme_options() const {
    return {o_.domain, o_.step_safety, o_.max_step_s, o_.threads};
  }

  double seconds(coupling::Tick n) const {
    return static_cast<double>(n) / static_cast<double>(tps_);
  }

  std::string where() const {
    if (const auto* s = solver(); s != nullptr && initialized_) {
      return fmt::format("domain '{}' at t = {:.6e} s (cycle {})", o_.domain, s->time_s(),
                         s->cycle());
    }
    return fmt::format("domain '{}'", o_.domain);
  }

  /// Scenario, cut, this domain's solver, its result file.
  void prepare() {
    auto read = io::read_scenario_with_hash(o_.scenario);  // one parse for both
    hash_ = std::move(read.hash);
    model_ = std::make_unique<model::Model>(std::move(read.model));
    const auto& entry = domain_scheme_named(o_.coupling);
    dec_ = std::make_unique<partition::Decomposition>(
        partition::decompose(*model_, entry.cut, entry.overlap_layers));
    scheme_ = entry.make(*dec_, *model_, scheme_options());
    elements_ = static_cast<std::int64_t>(solver()->model().element_count());
    solver()->initialize();
    initialized_ = true;
    injected_fault_cycle_ = injected_fault_cycle(o_.domain);
    checkpoints_ = std::make_unique<DaemonCheckpoints>(o_.out_dir, o_.domain, hash_, *dec_);
  }

  /// DIR/domains/<domain>.h5. Opened once the coordinator has accepted our Hello: a second daemon
  /// started for a domain that is running (refused: ERROR_CODE_DOMAIN_HELD) must not truncate the
  /// running daemon's file.
  void open_output() {
    output_ = std::make_unique<DomainOutput>(o_.out_dir, o_.domain, *solver());
    h5_path_ = output_->h5_path();
    link_->keep_alive();  // a large mesh takes a while to write
  }

  void connect() {
    auto session = o_.session;
    session.stop = o_.stop;
    link_ = std::make_unique<transport::DaemonLink>(
        o_.endpoint, transport::daemon_hello(o_.domain, hash_), session);
    tps_ = link_->coordinator_hello().ticks_per_second();
    if (tps_ < 1) {
      throw ProtocolError("coordinator",
                          fmt::format("the coordinator's Hello announces {} ticks per second; "
                                      "expected >= 1",
                                      tps_));
    }
    scheme_->set_ticks_per_second(tps_);
    open_output();
    output_->set_scheme_energy([this](double t_s) { return scheme_->scheme_energy(t_s); });
    output_->set_field_gate([this] { return scheme_->fields_settled(); });
    if (o_.offer_lane && scheme_->uses_lanes()) lanes_.open_own(o_.endpoint);
    link_->send(register_message(*scheme_, scheme_options(), tps_, checkpoints_->instants(),
                                 {lanes_.endpoint(), lanes_.public_key()}));
    const wire::Setup setup = await_setup();
    check_scheme(setup, o_.domain, o_.coupling);
    if (scheme_->start(setup)) {
      // A new solver (the Setup's masses): the recorder follows it.
      output_->follow(*solver());
    }
    // while it waits for its partners' rings: heartbeats, the stop flag, the coordinator's Error
    // (a partner failed: thrown at once), what else comes kept for the loop
    lanes_.connect(setup, scheme_->lane_partners(), [this] {
      if (o_.stop != nullptr && o_.stop->load())
        throw transport::StopRequested("stopped on request");
      while (auto m = link_->receive(std::chrono::milliseconds{0}))
        pending_.push_back(std::move(*m));
    });
    if (setup.restart()) {
      restore(setup.restart_ticks());
    } else {
      checkpoints_->remove_old();
      scheme_->initialize();
    }
    checkpoints_->plan(setup.options().checkpoint_interval_ticks(), scheme_->time());
    // What the scheme queues to send leaves at once: the domains compute at the same time
    // (docs/design.md §2.6 "Overlap").
    scheme_->set_on_outbox([this] { send_outbox(); });
    run_wall0_ = Clock::now();
    output_->set_setup_cpu(cpu_seconds() - cpu0_);  // this process's, as mono's (run_single)
  }

  /// link_->receive(timeout) in waits of at most 100 ms, checking the stop flag between them (the
  /// peer timeout is the link's own, from the last message heard, not from this call).
  std::optional<wire::Envelope> receive_or_stop(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
      if (o_.stop != nullptr && o_.stop->load())
        throw transport::StopRequested("stopped on request");
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
      const auto slice =
          std::clamp(left, std::chrono::milliseconds{0}, std::chrono::milliseconds{100});
      auto m = link_->receive(slice);
      if (m || left <= slice) return m;
    }
  }

  wire::Setup await_setup() {
    for (;;) {
      auto m = receive_or_stop(o_.session.peer_timeout);
      if (!m) continue;  // receive() itself throws when the coordinator is silent
      if (m->has_setup()) return m->setup();
      throw ProtocolError("coordinator",
                          fmt::format("expected the Setup answering the Register of domain '{}', "
                                      "got a {}",
                                      o_.domain, wire::body_name(*m)));
    }
  }

  /// The scheme's progress report (with the interface history rows), if it sends one.
  void send_report(bool checkpoint = false) {
    if (auto e = scheme_->report(checkpoint)) link_->send(*e);
  }

  /// Blocks until a partner's vector comes on our lane or the coordinator says something (an
  /// Error or a Bye is thrown or queued; heartbeats are swallowed); the coordinator's silence,
  /// and through it a partner's death, ends the wait (DaemonLink::keep_alive).
  void wait_on_lane() {
    const auto t0 = Clock::now();
    for (;;) {
      if (o_.stop != nullptr && o_.stop->load())
        throw transport::StopRequested("stopped on request");  // a partner may be frozen
      if (auto r = lanes_.receive(20ms, *scheme_)) {
        pending_.push_back(std::move(*r));
        break;
      }
      while (auto m = link_->receive(0ms)) pending_.push_back(std::move(*m));
      if (!pending_.empty()) break;
      link_->keep_alive();
    }
    wait_s_ += seconds_since(t0);
  }

  void loop() {
    using coupling::Pace;
    const auto service_every = std::max(o_.session.heartbeat_interval / 4, 1ms);
    auto next_service = Clock::now() + service_every;
    auto on_sample = [&] {
      if (o_.stop != nullptr && o_.stop->load())
        throw transport::StopRequested("stopped on request");
      if (injected_fault_cycle_ >= 0 && solver()->cycle() >= injected_fault_cycle_)
        throw std::logic_error(fmt::format(
            "injected at cycle {} by CRASHLINK_INJECT_INTERNAL_ERROR (a test of exit code 4)",
            solver()->cycle()));
      output_->sample();
      link_->keep_alive();
      // Between waits (a fine domain takes several steps per message), read what arrived: the
      // coordinator's heartbeats keep it alive here; other messages are delivered after advance().
      if (const auto now = Clock::now(); now >= next_service) {
        next_service = now + service_every;
        while (auto m = link_->receive(0ms)) pending_.push_back(std::move(*m));
        send_report();
      }
    };
    for (;;) {
      while (!pending_.empty()) {
        auto m = std::move(pending_.front());
        pending_.pop_front();
        scheme_->deliver(std::move(m));
      }
      const Pace pace = scheme_->advance(on_sample, checkpoints_->until(scheme_->end_time()));
      send_outbox();  // what the scheme queued without calling on_outbox (layer: g_A(0))
      if (pace == Pace::Finished) return;
      // Paused: at `until` (`layer` with variable steps: at the first instant of the leader at
      // or after it, which a follower's owner marks).
      if (pace == Pace::Paused && scheme_->at_cycle_boundary() && checkpoints_->enabled()) {
        write_checkpoint();
        continue;
      }
      // What on_sample read meanwhile may be the very message the scheme waits for: deliver it
      // before blocking (the partner, served early by set_on_outbox, often answers mid-advance).
      if (pace == Pace::Paused || !pending_.empty()) continue;
      if (lanes_.active()) {
        wait_on_lane();
        continue;
      }
      const auto t0 = Clock::now();
      auto m = receive_or_stop(o_.session.peer_timeout);
      wait_s_ += seconds_since(t0);
      if (m) scheme_->deliver(std::move(*m));
    }
  }

  void send_outbox() {
    scheme_->drain_outbox([this](const coupling::Outgoing& m) {
      if (!lanes_.send(m.interface_index, m.envelope)) link_->send(m.envelope);
    });
  }

  void finish() {
    send_report();
    output_->finish(seconds_since(wall0_), run_cpu_seconds(), elements_);
    // A partner may still open our ring (docs/processes.md "Lanes"); the coordinator's Error
    // (a partner failed) is thrown here, a Bye (none is sent today) would end the wait.
    bool bye_seen = false;
    const bool held = lanes_.hold_until_opened(o_.session.peer_timeout, [&] {
      if (o_.stop != nullptr && o_.stop->load())
        throw transport::StopRequested("stopped on request");
      while (!bye_seen) {  // receive() sends the heartbeats and judges the coordinator's silence
        const auto m = link_->receive(std::chrono::milliseconds{0});
        if (!m) break;
        bye_seen = m->has_bye();
      }
      return !bye_seen;
    });
    if (!held && !bye_seen) {
      std::fprintf(stderr,
                   "crashlink-solver: domain '%s': a partner has not opened this daemon's lane "
                   "within %lld ms; ending anyway\n",
                   o_.domain.c_str(), static_cast<long long>(o_.session.peer_timeout.count()));
    }
    // An Error the coordinator sent meanwhile (another domain failed at the end) is read now, not
    // after a Bye that a coordinator already gone would leave blocked for the send timeout.
    while (!bye_seen) {
      const auto m = link_->receive(std::chrono::milliseconds{0});
      if (!m || m->has_bye()) break;
    }
    wire::Envelope bye = transport::make_bye("end time reached");
    auto* rep = bye.mutable_bye()->mutable_report();
    const auto& s = *solver();
    rep->set_cpu_seconds(run_cpu_seconds());
    rep->set_wait_seconds(wait_s_);
    rep->set_wall_seconds(seconds_since(run_wall0_));
    rep->set_cycles(s.cycle());
    rep->set_dt_min_s(s.dt_min_s());
    rep->set_elements(elements_);
    rep->set_time_ticks(scheme_->time());
    scheme_->fill_bye(*rep);
    link_->send(bye);
  }

  const DaemonOptions& o_;
  Clock::time_point wall0_, run_wall0_;
  double cpu0_ = 0.0;
  double wait_s_ = 0.0;
  std::string hash_;
  std::int64_t tps_ = 0;
  std::int64_t elements_ = 0;
  bool initialized_ = false;
  std::string h5_path_;
  // Owners before users: the sub-models outlive the solver, the writer the recorder.
  std::unique_ptr<model::Model> model_;
  std::unique_ptr<partition::Decomposition> dec_;
  std::unique_ptr<coupling::DomainScheme> scheme_;
  std::unique_ptr<DomainOutput> output_;
  std::unique_ptr<transport::DaemonLink> link_;
  DaemonLanes lanes_{o_.domain, o_.session};
  std::deque<wire::Envelope> pending_;
  std::unique_ptr<DaemonCheckpoints> checkpoints_;
  double cpu_before_ = 0.0;  ///< CPU of the runs before the checkpoint restarted from
  std::int64_t injected_fault_cycle_ = -1;  ///< CRASHLINK_INJECT_INTERNAL_ERROR's cycle here
};

}  // namespace

DaemonResult run_daemon(const DaemonOptions& options) {
  return Daemon(options).run();
}

}  // namespace crashlink::daemon
