#include "solver/daemon/daemon.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

#include "solver/core/errors.h"
#include "solver/core/log_escape.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_stepper.h"
#include "solver/daemon/apply_setup.h"
#include "solver/daemon/layer_wire.h"
#include "solver/daemon/paper_port.h"
#include "solver/io/result_writer.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "solver/run/checkpoint_store.h"
#include "solver/run/cpu_clock.h"
#include "solver/run/domain_checkpoint.h"
#include "solver/run/domain_recorder.h"
#include "solver/run/exit_codes.h"
#include "transport/curve_errors.h"
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

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Where one partner's layer vectors leave: its ZeroMQ lane or its shared-memory lane.
struct LaneOut {
  std::unique_ptr<transport::Dealer> zmq;
  std::unique_ptr<transport::ShmLaneOut> shm;
  void send(const wire::Envelope& e) {
    if (zmq) {
      zmq->send(e);
    } else {
      shm->send_message(e);
    }
  }
};

/// Thrown from the sample hook when DaemonOptions::stop is set.
struct Stopped {};

/// How a failure ends the daemon.
struct Failure {
  int exit_code = run::kExitInternal;
  wire::ErrorCode code = wire::ERROR_CODE_INTERNAL;
  bool tell_coordinator = true;  ///< false when the coordinator is the one who stopped us
  std::string text;
};

class Daemon {
 public:
  explicit Daemon(const DaemonOptions& o) : o_(o) {}

  DaemonResult run() {
    wall0_ = Clock::now();
    cpu0_ = cpu_seconds();
    std::optional<Failure> failure;
    try {
      prepare();
      connect();
      loop();
      finish();
    } catch (const transport::StopRequested&) {
      failure = Failure{run::kExitStopped, wire::ERROR_CODE_STOPPED, true,
                        fmt::format("{}: stopped on request (signal)", where())};
    } catch (const Stopped&) {
      failure = Failure{run::kExitStopped, wire::ERROR_CODE_STOPPED, true,
                        fmt::format("{}: stopped on request (signal)", where())};
    } catch (const transport::RemoteError& e) {
      const bool refused = e.code() == wire::ERROR_CODE_VERSION_MISMATCH ||
                           e.code() == wire::ERROR_CODE_SCENARIO_MISMATCH ||
                           e.code() == wire::ERROR_CODE_DOMAIN_HELD;
      const int exit_code = refused                                ? run::kExitInput
                            : e.code() == wire::ERROR_CODE_STOPPED ? run::kExitStopped
                                                                   : run::kExitPeer;
      failure = Failure{exit_code, e.code(), false,
                        fmt::format("{}: {} by the coordinator: {}", where(),
                                    refused ? "refused" : "stopped", e.what())};
    } catch (const transport::PeerTimeoutError& e) {
      failure = Failure{run::kExitPeer, wire::ERROR_CODE_TIMEOUT, true,
                        fmt::format("{}: {}", where(), e.what())};
    } catch (const transport::TransportError& e) {
      failure = Failure{run::kExitPeer, wire::ERROR_CODE_INTERNAL, true,
                        fmt::format("{}: {}", where(), e.what())};
    } catch (const transport::ProtocolError& e) {
      failure = Failure{run::kExitPeer, wire::ERROR_CODE_PROTOCOL, true,
                        fmt::format("{}: protocol error: {}", where(), e.what())};
    } catch (const NumericalError& e) {
      failure = Failure{run::kExitNumerical, wire::ERROR_CODE_NUMERICAL, true,
                        fmt::format("{}: {}", where(), e.what())};
    } catch (const transport::CurveRefusedError& e) {
      // Refused by the coordinator's CURVE check: a second handshake would be refused too.
      failure = Failure{run::kExitInput, wire::ERROR_CODE_PROTOCOL, false,
                        fmt::format("{}: {}", where(), e.what())};
    } catch (const IoError& e) {
      failure = Failure{run::kExitIo, wire::ERROR_CODE_IO, true,
                        fmt::format("{}: I/O error: {}", where(), e.what())};
    } catch (const std::filesystem::filesystem_error& e) {
      failure = Failure{run::kExitIo, wire::ERROR_CODE_IO, true,
                        fmt::format("{}: I/O error: {}", where(), e.what())};
    } catch (const InputError& e) {
      failure = Failure{run::kExitInput, wire::ERROR_CODE_MODEL, true,
                        fmt::format("{}: input error: {}", where(), e.what())};
    } catch (const ModelError& e) {
      failure = Failure{run::kExitInput, wire::ERROR_CODE_MODEL, true,
                        fmt::format("{}: model error: {}", where(), e.what())};
    } catch (const std::exception& e) {
      failure = Failure{run::kExitInternal, wire::ERROR_CODE_INTERNAL, true,
                        fmt::format("{}: internal error: {}", where(), e.what())};
    }
    DaemonResult r;
    if (failure) {
      if (failure->tell_coordinator) tell(*failure);
      close_output_after_failure();
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
  integration::Solver* solver() const {
    return paper_ ? paper_->solver.get() : dom_ ? dom_->solver.get() : nullptr;
  }

  /// The instant reached, in ticks.
  cosim::Tick time_ticks() const { return paper_ ? paper_time_ : stepper_ ? stepper_->time() : 0; }

  double cpu_seconds() const {
    return o_.in_process ? thread_cpu_seconds() : run::process_cpu_seconds();
  }

  /// CPU of this run, plus that of the run(s) before the checkpoint it restarted from.
  double run_cpu_seconds() const { return cpu_before_ + cpu_seconds() - cpu0_; }

  static constexpr cosim::Tick max_tick() { return std::numeric_limits<cosim::Tick>::max(); }

  /// docs/design.md §2.6 "Checkpoints": between two cycles at a multiple of the coordinator's
  /// interval, with every message up to this instant sent and consumed (LayerStepper::save_state).
  /// The result file's rows so far go along as a copy, so a restart rebuilds its file from it.
  void write_checkpoint() {
    const cosim::Tick T = stepper_->time();
    send_report(true);  // the interface history up to T, which the coordinator's checkpoint holds
    run::write_domain_checkpoint(checkpoint_site(), T, stepper_->seconds(T), *recorder_, *solver(),
                                 run_cpu_seconds(), [this](core::StateWriter& w) {
                                   w.put_double("run.wait_seconds", wait_s_);
                                   stepper_->save_state(w);
                                 });
  }

  /// Resumes from this domain's checkpoint at T (the coordinator's choice, from our Register).
  void restore(cosim::Tick T) {
    cpu_before_ = run::restore_domain_checkpoint(checkpoint_site(), T, stepper_->seconds(T),
                                                 *recorder_, *solver(),
                                                 [this](const core::StateReader& r) {
                                                   stepper_->restore_state(r);
                                                   wait_s_ = r.get_double("run.wait_seconds");
                                                 })
                      .cpu_seconds;
  }

  /// This domain's checkpoints: a coupled run's, pruned by every piece of the cut.
  run::DomainCheckpointSite checkpoint_site() const {
    return {o_.out_dir,
            o_.domain,
            hash_,
            run::kCoupledKind,
            checkpoint_pieces(),
            fmt::format("crashlink-solver: domain '{}'", o_.domain)};
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
    dec_ = std::make_unique<partition::Decomposition>(partition::decompose(
        *model_, o_.paper ? partition::Scheme::Paper : partition::Scheme::Layer));
    if (o_.paper) {
      paper_ = std::make_unique<PaperPort>(build_paper_port(*dec_, o_.domain));
    } else {
      dom_ = std::make_unique<cosim::LayerDomain>(
          cosim::build_layer_domain(*dec_, *model_, o_.domain));
    }
    elements_ = static_cast<std::int64_t>(solver()->model().element_count());
    solver()->initialize();
    initialized_ = true;
    read_injected_fault();
    std::vector<std::string> damaged;
    checkpoints_ = run::list_sound_checkpoints(o_.out_dir, o_.domain, &damaged);
    for (const auto& d : damaged)
      std::fprintf(stderr,
                   "crashlink-solver: domain '%s': checkpoint damaged, not offered for a restart: "
                   "%s\n",
                   o_.domain.c_str(), d.c_str());
  }

  /// DIR/domains/<domain>.h5 and its recorder. Opened once the coordinator has accepted our
  /// Hello: a second daemon started for a domain that is running (refused: ERROR_CODE_DOMAIN_HELD)
  /// must not truncate the running daemon's file.
  void open_output() {
    io::ResultWriterOptions wo;
    wo.file_stem = o_.domain;  // DIR/domains/<domain>.h5, what solver/gather reads back
    // A daemon may be killed by a failure elsewhere: keep at most a second of history unwritten.
    wo.history_flush_wall_s = 1.0;
    writer_ = std::make_unique<io::ResultWriter>(
        (std::filesystem::path(o_.out_dir) / "domains").string(), solver()->model(), wo);
    h5_path_ = writer_->h5_path();
    recorder_ = std::make_unique<run::DomainRecorder>(*writer_, *solver());
    link_->keep_alive();  // a large mesh takes a while to write
  }

  /// Every domain of the cut, and the coordinator when it keeps state (a cut with an interface).
  std::vector<std::string> checkpoint_pieces() const {
    std::vector<std::string> names;
    for (const auto& d : dec_->domains) names.push_back(d.name);
    return run::checkpoint_pieces(std::move(names), !dec_->interfaces.empty());
  }

  /// CRASHLINK_INJECT_INTERNAL_ERROR=DOMAIN:CYCLE makes this domain throw an unexpected exception
  /// at that cycle: the one way to see, end to end, what a bug does to a run (exit 4 here, 5 for
  /// the others, 4 from the launcher; docs/processes.md "Exit codes"). Ignored unless it names
  /// this domain.
  void read_injected_fault() {
    const char* v = std::getenv("CRASHLINK_INJECT_INTERNAL_ERROR");
    if (v == nullptr) return;
    const std::string s(v);
    const auto colon = s.rfind(':');
    if (colon == std::string::npos || s.substr(0, colon) != o_.domain) return;
    try {
      injected_fault_cycle_ = std::stoll(s.substr(colon + 1));
    } catch (const std::exception&) {
      throw InputError(fmt::format("CRASHLINK_INJECT_INTERNAL_ERROR='{}': expected DOMAIN:CYCLE",
                                   core::log_escape(s)));
    }
  }

  void connect() {
    auto session = o_.session;
    session.stop = o_.stop;
    link_ = std::make_unique<transport::DaemonLink>(
        o_.endpoint, transport::daemon_hello(o_.domain, hash_), session);
    tps_ = link_->coordinator_hello().ticks_per_second();
    if (tps_ < 1) {
      throw transport::ProtocolError(
          "coordinator", fmt::format("the coordinator's Hello announces {} ticks per second; "
                                     "expected >= 1",
                                     tps_));
    }
    open_output();
    if (!o_.paper) open_own_lane();
    link_->send(register_message());
    const wire::Setup setup = await_setup();
    check_coupling(setup);
    if (o_.paper) {
      start_paper(setup);
      return;
    }
    apply_setup(setup);
    open_lanes(setup);
    stepper_ = std::make_unique<cosim::LayerStepper>(
        *solver(), std::move(dom_->ports), setup.step_ticks(), tps_,
        !setup.variable_steps()            ? cosim::LayerSteps::Fixed
        : setup.mode() == wire::MODE_SPLIT ? cosim::LayerSteps::VariableCommon
                                           : cosim::LayerSteps::Variable);
    stepper_->set_record_history(true);
    if (setup.variable_steps())
      stepper_->set_proposal_limits(o_.step_safety, o_.max_step_s);
    else
      stepper_->set_end_time(setup.end_time_ticks());
    if (setup.restart()) {
      restore(setup.restart_ticks());
    } else {
      run::remove_checkpoints(o_.out_dir, o_.domain);  // another run's: not to be mixed with ours
      stepper_->initialize();
    }
    checkpoint_every_ = setup.options().checkpoint_interval_ticks();
    next_checkpoint_ = checkpoint_every_ > 0
                           ? (stepper_->time() / checkpoint_every_ + 1) * checkpoint_every_
                           : std::numeric_limits<cosim::Tick>::max();
    // u_J(T + H) leaves before the coarse side's nodal passes, g_A right after the fine side's: the
    // domains compute at the same time (LayerStepper::set_on_outbox, docs/design.md §2.6
    // "Overlap").
    stepper_->set_on_outbox([this] { send_outbox(); });
    run_wall0_ = Clock::now();
  }

  /// `paper`, every cycle: proposal_ticks(), with a stable step that collapsed (NaN, or below one
  /// tick) ending the run as the numerical failure it is.
  std::int64_t paper_proposal() const {
    const double dt = solver()->dt_s();
    if (std::isnan(dt) ||
        (std::isfinite(dt) && !(o_.step_safety * dt * static_cast<double>(tps_) >= 1.0)))
      throw NumericalError(fmt::format(
          "the stable step is {:.6e} s (set by {}), below one tick of 1/{} s: the mesh has "
          "collapsed there; fix: check that element's material, contact and loading",
          dt, solver()->critical_element(), tps_));
    return proposal_ticks();
  }

  /// This domain's step proposal in whole ticks: floor(step_safety * min(dt, max_step_s) * tps),
  /// dt the solver's own stable step (LayerNetworkOptions' rule, layer_network.cpp, so both plan
  /// the same steps); 0: no limit (no deformable element).
  std::int64_t proposal_ticks() const {
    const auto& s = *solver();
    double dt = s.dt_s();
    if (o_.max_step_s > 0.0) dt = std::min(dt, o_.max_step_s);
    if (!std::isfinite(dt)) return 0;
    const double x = std::floor(o_.step_safety * dt * static_cast<double>(tps_));
    if (!(x >= 1.0) || x > 4.0e18) {
      throw ModelError(
          fmt::format("the stable step {:.6e} s is not a whole number of ticks of 1/{} s (at "
                      "least one)",
                      dt, tps_));
    }
    return static_cast<std::int64_t>(x);
  }

  wire::Envelope register_message() const {
    const auto& s = *solver();
    const auto& sub = s.model();
    wire::Envelope e;
    auto* r = e.mutable_registration();
    const std::int64_t proposal = proposal_ticks();
    r->set_stable_step_ticks(proposal);
    r->set_stable_step_s(s.dt_s());
    r->set_end_time_s(sub.controls.end_time_s);
    r->set_end_time_ticks(static_cast<std::int64_t>(
        std::llround(sub.controls.end_time_s * static_cast<double>(tps_))));
    r->set_elements(elements_);
    if (paper_) {
      for (std::size_t j = 0; j < paper_->nodes.size(); ++j) {
        const auto l = paper_->nodes[j].local;
        r->add_node_ids(sub.nodes.id[l]);
        r->add_masses_kg(paper_->own_mass_kg[j]);
        for (std::size_t d = 0; d < 3; ++d) r->add_positions_m(sub.nodes.x0[3 * l + d]);
      }
      return e;
    }
    for (const auto t : checkpoints_) r->add_checkpoint_ticks(t);
    r->set_lane_endpoint(lane_endpoint_);
    if (lane_in_) r->set_lane_public_key(lane_in_->curve_public_key());
    for (const auto& port : dom_->ports) {
      auto* li = r->add_layer_interfaces();
      li->set_index(port.index);
      li->set_fine_side(port.fine_side);
      for (const auto l : port.local) {
        li->add_j_node_ids(sub.nodes.id[l]);
        li->add_masses_kg(port.fine_side ? 0.0 : s.mass()[l]);
        for (std::size_t d = 0; d < 3; ++d) li->add_positions_m(sub.nodes.x0[3 * l + d]);
      }
    }
    return e;
  }

  /// link_->receive(timeout) in waits of at most 100 ms, checking the stop flag between them (the
  /// peer timeout is the link's own, from the last message heard, not from this call).
  std::optional<wire::Envelope> receive_or_stop(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
      if (o_.stop != nullptr && o_.stop->load()) throw Stopped();
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
      throw transport::ProtocolError(
          "coordinator", fmt::format("expected the Setup answering the Register of domain '{}', "
                                     "got a {}",
                                     o_.domain, body_name(*m)));
    }
  }

  /// Both sides must run the same scheme: a `layer` daemon cannot serve a `paper` coordinator.
  void check_coupling(const wire::Setup& setup) const {
    const auto want = o_.paper ? wire::COUPLING_PAPER : wire::COUPLING_LAYER;
    if (setup.coupling() == want) return;
    throw transport::ProtocolError(
        "coordinator",
        fmt::format("the coordinator runs the {} scheme, but domain '{}' was started for {}: "
                    "start crashlink-solver and crashlink-coordinator with the same --coupling",
                    wire::Coupling_Name(setup.coupling()), o_.domain, wire::Coupling_Name(want)));
  }

  /// `paper`: the Setup's summed masses ([5]; the solver is rebuilt if they differ in any bit
  /// from the cut's), no checkpoints, no restart.
  void start_paper(const wire::Setup& setup) {
    if (setup.ticks_per_second() != tps_ || setup.step_ticks() < 1)
      throw transport::ProtocolError(
          "coordinator",
          fmt::format("`paper` Setup for domain '{}' with step {} ticks at {} ticks "
                      "per second (Hello: {})",
                      o_.domain, setup.step_ticks(), setup.ticks_per_second(), tps_));
    if (setup.restart() || setup.options().checkpoint_interval_ticks() > 0)
      throw transport::ProtocolError(
          "coordinator", fmt::format("the `paper` Setup of domain '{}' asks for checkpoints or a "
                                     "restart; `paper` runs have neither (use `layer`)",
                                     o_.domain));
    if (auto fresh = use_summed_masses(*paper_, setup, o_.domain)) {
      // The recorder moves to the new solver before the old one is destroyed.
      fresh->initialize();
      recorder_ = std::make_unique<run::DomainRecorder>(*writer_, *fresh);
      paper_->solver = std::move(fresh);
    }
    run::remove_checkpoints(o_.out_dir, o_.domain);
    paper_step_ = setup.step_ticks();
    run_wall0_ = Clock::now();
  }

  /// `paper` (docs/design.md §2.6): send the free state at t, wait for its Correction, apply it,
  /// begin the cycle (energies at t, guard, output), take the imposed step; the next free state
  /// carries the energies at t. Every wait is bounded by the peer timeout.
  void paper_loop() {
    auto& s = *solver();
    wire::Envelope out;  // reused: its arrays keep their capacity
    cosim::Tick energy_time = -1;
    for (;;) {
      // Our own proposal: the coordinator imposes it (variable steps) or its plan (fixed).
      fill_free_state(*paper_, paper_time_, paper_proposal(), paper_energy_, energy_time, out);
      link_->send(out);
      const wire::Correction c = await_correction();
      apply_correction(*paper_, c, o_.domain);
      // At the end no step follows; the last one (or the stable step, if it shrank below it)
      // keeps the last kinetic energy (product form, v^{n+1/2} over dt^{n+1/2}) on the steps the
      // run took, as in every cycle before.
      if (!c.stop()) paper_step_ = c.imposed_step_ticks();
      const double step_s = static_cast<double>(paper_step_) / static_cast<double>(tps_);
      s.impose_step(c.stop() ? std::min(step_s, s.dt_s()) : step_s);
      s.begin_cycle();
      if (o_.stop != nullptr && o_.stop->load()) throw Stopped();
      recorder_->sample();
      link_->keep_alive();
      paper_energy_ = energy_terms(*paper_);
      energy_time = paper_time_;
      if (c.stop()) return;
      s.end_cycle_forces();
      s.end_cycle_accelerations();
      paper_time_ += c.imposed_step_ticks();
    }
  }

  /// The Correction of the free state at paper_time_ (heartbeats are swallowed by the link; an
  /// Error from the coordinator is thrown by it).
  wire::Correction await_correction() {
    const auto t0 = Clock::now();
    for (;;) {
      // A heartbeat interval at a time, to honour a stop request while waiting.
      auto m =
          link_->receive(std::max(o_.session.heartbeat_interval, std::chrono::milliseconds{1}));
      if (o_.stop != nullptr && o_.stop->load()) throw Stopped();
      if (!m) continue;  // receive() itself throws when the coordinator is silent
      if (!m->has_correction())
        throw transport::ProtocolError(
            "coordinator", fmt::format("domain '{}' expected the Correction of its free state at "
                                       "tick {}, got a {}",
                                       o_.domain, paper_time_, body_name(*m)));
      if (m->correction().time_ticks() != paper_time_)
        throw transport::ProtocolError(
            "coordinator", fmt::format("domain '{}' got a Correction for tick {}; its free state "
                                       "is at tick {}",
                                       o_.domain, m->correction().time_ticks(), paper_time_));
      wait_s_ += seconds_since(t0);
      return std::move(*m->mutable_correction());
    }
  }

  void apply_setup(const wire::Setup& setup) {
    daemon::apply_setup(setup, tps_, o_.domain, dom_->ports);  // solver/daemon/apply_setup.h
  }

  /// Our lane (docs/processes.md "Lanes"), bound before the Register that announces it. A lane
  /// that cannot be bound is not offered (the coordinator then routes this domain's vectors).
  void open_own_lane() {
    if (!o_.offer_lane) return;
    const auto lane = transport::lane_endpoint_for(o_.endpoint, o_.domain, o_.session.socket.curve);
    try {
      if (lane.rfind(transport::kShmScheme, 0) == 0) {
        shm_in_ = std::make_unique<transport::ShmLaneIn>(lane.substr(transport::kShmScheme.size()));
        lane_endpoint_ = shm_in_->endpoint();
      } else if (!lane.empty()) {
        // Across hosts a CURVE server with this daemon's own key; the partners' keys come with
        // the Setup (Router::authorize), a partner connecting earlier waits for them.
        auto options = o_.session.socket;
        options.curve.authorize_later = true;
        lane_in_ = std::make_unique<transport::Router>(lane, options);
        lane_endpoint_ = lane_in_->endpoint();
      }
    } catch (const transport::TransportError& e) {
      std::fprintf(stderr,
                   "crashlink-solver: domain '%s': no lane (%s); the coordinator routes this "
                   "domain's layer vectors\n",
                   o_.domain.c_str(), e.what());
      shm_in_.reset();
      lane_in_.reset();
      lane_endpoint_.clear();
    }
  }

  /// The Setup's lanes: a Dealer to each partner's lane, named by our domain; every interface's
  /// vectors then leave on its partner's lane. No lanes: they go to the coordinator.
  void open_lanes(const wire::Setup& setup) {
    if (setup.lanes_size() == 0) return;
    if (lane_endpoint_.empty()) {
      throw transport::ProtocolError(
          "coordinator", fmt::format("the Setup of domain '{}' lists {} lanes, but this daemon "
                                     "offered none",
                                     o_.domain, setup.lanes_size()));
    }
    std::vector<std::string> partner_keys;  // the clients our CURVE lane accepts
    for (const auto& lane : setup.lanes()) {
      LaneOut out;
      if (lane.endpoint().rfind(transport::kShmScheme, 0) == 0) {
        if (!shm_in_) {
          throw transport::ProtocolError(
              "coordinator",
              fmt::format("the Setup of domain '{}' gives '{}' the shared-memory "
                          "lane {}, but this daemon's lane is {}",
                          o_.domain, core::log_escape(lane.domain()),
                          core::log_escape(lane.endpoint(), core::kLogTextBytes), lane_endpoint_));
        }
        // Its vectors to us, created before it can send: room for 8 of the largest (two 3-vectors
        // of doubles per J node, plus the envelope).
        std::size_t largest = 0;
        for (const auto& port : dom_->ports)
          if (port.partner == lane.domain()) largest = std::max(largest, port.local.size());
        shm_in_->add_partner(lane.domain(), 8 * (48 * largest + 1024));
        out.shm = std::make_unique<transport::ShmLaneOut>(lane.endpoint(), o_.domain,
                                                          o_.session.peer_timeout);
      } else {
        auto options = o_.session.socket;
        options.curve.server_key = lane.public_key();  // used when CURVE is on for that endpoint
        out.zmq = std::make_unique<transport::Dealer>(lane.endpoint(), o_.domain, options);
        partner_keys.push_back(lane.public_key());
      }
      lanes_out_.emplace(lane.domain(), std::move(out));
    }
    if (lane_in_) lane_in_->authorize(std::move(partner_keys));
    for (const auto& port : dom_->ports) {
      const auto it = lanes_out_.find(port.partner);
      if (it == lanes_out_.end()) {
        throw transport::ProtocolError(
            "coordinator", fmt::format("the Setup of domain '{}' has no lane to '{}', its "
                                       "partner on interface {}",
                                       o_.domain, port.partner, port.index));
      }
      if (lane_of_.size() <= port.index) lane_of_.resize(port.index + 1, nullptr);
      lane_of_[port.index] = &it->second;
    }
  }

  /// Progress and the interface history rows completed since the last report (LayerReport).
  void send_report(bool checkpoint = false) {
    wire::Envelope e;
    auto* rep = e.mutable_layer_report();
    rep->set_time_ticks(stepper_->time());
    rep->set_checkpoint(checkpoint);
    for (const auto& h : stepper_->take_history()) {
      auto* rows = rep->add_rows();
      rows->set_interface_index(h.interface_index);
      for (const auto& row : h.rows) {
        rows->add_time_ticks(row.time);
        for (const double f : row.force_N) rows->add_force_n(f);
        rows->add_link_work_j(row.link_work_J);
      }
    }
    link_->send(e);
  }

  /// Blocks until a partner's vector comes on our lane or the coordinator says something (an
  /// Error or a Bye is thrown or queued; heartbeats are swallowed); the coordinator's silence,
  /// and through it a partner's death, ends the wait (DaemonLink::keep_alive).
  void wait_on_lane() {
    const auto t0 = Clock::now();
    for (;;) {
      if (o_.stop != nullptr && o_.stop->load()) throw Stopped();  // a partner may be frozen
      if (auto r = receive_lane()) {
        pending_.push_back(std::move(*r));
        break;
      }
      while (auto m = link_->receive(0ms)) pending_.push_back(std::move(*m));
      if (!pending_.empty()) break;
      link_->keep_alive();
    }
    wait_s_ += seconds_since(t0);
  }

  static std::string body_name(const wire::Envelope& e) {
    const auto* field = wire::Envelope::descriptor()->FindFieldByNumber(e.body_case());
    return field != nullptr ? field->name() : "empty Envelope";
  }

  void loop() {
    if (paper_) {
      paper_loop();
      return;
    }
    using Wait = cosim::LayerStepper::Wait;
    const auto service_every = std::max(o_.session.heartbeat_interval / 4, 1ms);
    auto next_service = Clock::now() + service_every;
    auto on_sample = [&] {
      if (o_.stop != nullptr && o_.stop->load()) throw Stopped();
      if (injected_fault_cycle_ >= 0 && solver()->cycle() >= injected_fault_cycle_)
        throw std::logic_error(fmt::format(
            "injected at cycle {} by CRASHLINK_INJECT_INTERNAL_ERROR (a test of exit code 4)",
            solver()->cycle()));
      recorder_->sample();
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
        deliver(m);
      }
      const cosim::Tick until =
          next_checkpoint_ < stepper_->end_time() ? next_checkpoint_ : max_tick();
      Wait w = Wait::None;
      try {
        w = stepper_->advance(on_sample, until);
      } catch (const cosim::LayerPartnerError& x) {
        throw transport::ProtocolError("partner", x.what());
      }
      send_outbox();  // g_A(0) after initialize(); otherwise sent from advance() already
      if (w == Wait::Finished) return;
      // Paused (LayerStepper::advance): at `until`, or with variable steps at the first instant
      // of the leader at or after it, which a follower's owner marks.
      if (w == Wait::None && stepper_->at_cycle_boundary() && checkpoint_every_ > 0) {
        write_checkpoint();
        next_checkpoint_ = (stepper_->time() / checkpoint_every_ + 1) * checkpoint_every_;
        continue;
      }
      // What on_sample read meanwhile may be the very message the stepper waits for: deliver it
      // before blocking (the partner, served early by set_on_outbox, often answers mid-advance).
      if (w == Wait::None || !pending_.empty()) continue;
      if (!lanes_out_.empty()) {
        wait_on_lane();
        continue;
      }
      const auto t0 = Clock::now();
      auto m = receive_or_stop(o_.session.peer_timeout);
      wait_s_ += seconds_since(t0);
      if (m) deliver(*m);
    }
  }

  /// A partner's vector from our lane within 20 ms, or nullopt; anything else is a ProtocolError.
  std::optional<wire::Envelope> receive_lane() {
    std::string peer, what;
    wire::Envelope e;
    bool ok = false;
    if (shm_in_) {
      if (!shm_in_->receive_into(20ms, peer, lane_bytes_)) return std::nullopt;
      ok = e.ParseFromString(lane_bytes_);
      if (!ok) what = fmt::format("{} bytes that are not an Envelope", lane_bytes_.size());
    } else {
      auto r = lane_in_->receive(20ms);
      if (!r) return std::nullopt;
      peer = r->peer;
      ok = r->ok();
      what = ok ? std::string() : r->error;
      if (ok) e = std::move(r->envelope);
    }
    if (!ok || lanes_out_.find(peer) == lanes_out_.end() ||
        !(e.has_layer_displacement() || e.has_layer_force())) {
      throw transport::ProtocolError(
          "lane", fmt::format("domain '{}' got {} on its lane {} from '{}'; a lane carries only "
                              "its partners' layer vectors",
                              o_.domain, ok ? body_name(e) : what, lane_endpoint_,
                              transport::printable_peer(peer)));
    }
    return e;
  }

  void send_outbox() {
    for (const auto& m : stepper_->take_outbox()) {
      if (m.interface_index < lane_of_.size() && lane_of_[m.interface_index] != nullptr) {
        lane_of_[m.interface_index]->send(to_envelope(m));
      } else {
        link_->send(to_envelope(m));
      }
    }
  }

  void deliver(const wire::Envelope& e) {
    auto m = to_layer_message(e);
    if (!m) {
      if (e.has_bye()) {
        throw transport::ProtocolError(
            "coordinator", fmt::format("the coordinator ended the session ({}) before domain '{}' "
                                       "reached the end time",
                                       core::log_escape(e.bye().reason()), o_.domain));
      }
      throw transport::ProtocolError(
          "coordinator",
          fmt::format("unexpected {} during the run of domain '{}'", body_name(e), o_.domain));
    }
    try {
      stepper_->deliver(std::move(*m));
    } catch (const ModelError& x) {
      throw transport::ProtocolError("coordinator", x.what());
    }
  }

  void finish() {
    if (stepper_) send_report();
    recorder_->finish();
    write_timing();
    writer_->close();
    // An Error the coordinator sent meanwhile (another domain failed at the end) is read now, not
    // after a Bye that a coordinator already gone would leave blocked for the send timeout.
    while (auto m = link_->receive(std::chrono::milliseconds{0}))
      if (m->has_bye()) break;
    wire::Envelope bye = transport::make_bye("end time reached");
    auto* rep = bye.mutable_bye()->mutable_report();
    const auto& s = *solver();
    rep->set_cpu_seconds(run_cpu_seconds());
    rep->set_wait_seconds(wait_s_);
    rep->set_wall_seconds(seconds_since(run_wall0_));
    rep->set_cycles(s.cycle());
    rep->set_dt_min_s(s.dt_min_s());
    rep->set_elements(elements_);
    rep->set_time_ticks(time_ticks());
    if (paper_) *rep->mutable_energy() = paper_energy_;  // the guard's last sample
    link_->send(bye);
  }

  /// The domain's timing and the spot welds that let go in it (gathered into result.h5).
  void write_timing() {
    const auto* s = solver();
    writer_->write_timing(seconds_since(wall0_), 0.0,
                          {{o_.domain, run_cpu_seconds(), s != nullptr ? s->cycle() : 0,
                            s != nullptr ? s->dt_min_s() : 0.0, elements_}});
    if (s == nullptr) return;
    std::vector<io::SpotWeldFailure> welds;
    for (const auto& w : s->weld_failures())
      welds.push_back({w.name, w.time_s, w.normal_N, w.shear_N});
    writer_->write_spot_weld_failures(welds);
  }

  /// Reports the failure to the coordinator, best effort (it may be the one that is gone). Before
  /// the session exists, a short handshake is tried so that the run stops at once.
  void tell(const Failure& f) {
    try {
      // (not for a stop on request: it must end within 1 s, and the coordinator has its own)
      if (!link_ && !hash_.empty() && f.code != wire::ERROR_CODE_STOPPED) {
        auto quick = o_.session;
        quick.handshake_timeout =
            std::min(quick.handshake_timeout, std::chrono::milliseconds{2000});
        link_ = std::make_unique<transport::DaemonLink>(
            o_.endpoint, transport::daemon_hello(o_.domain, hash_), quick);
      }
      if (link_ && link_->open()) link_->send_error(f.code, f.text);
    } catch (const std::exception&) {
      // Nobody to tell: the exit code and the message on stderr say it.
    }
  }

  void close_output_after_failure() {
    if (!writer_ || !writer_->is_open()) return;
    try {
      recorder_->flush();
      write_timing();
    } catch (const std::exception&) {
    }
    try {
      writer_->close();
    } catch (const std::exception&) {
    }
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
  std::unique_ptr<cosim::LayerDomain> dom_;
  std::unique_ptr<PaperPort> paper_;  ///< `paper`: this domain (instead of dom_ and stepper_)
  cosim::Tick paper_time_ = 0;        ///< `paper`: the instant of the next free state
  cosim::Tick paper_step_ = 0;        ///< `paper`: the last imposed step (first: the Setup's)
  wire::EnergyTerms paper_energy_;    ///< `paper`: the energies at the last begun instant
  std::unique_ptr<io::ResultWriter> writer_;
  std::unique_ptr<run::DomainRecorder> recorder_;
  std::unique_ptr<cosim::LayerStepper> stepper_;
  std::unique_ptr<transport::DaemonLink> link_;
  std::string lane_endpoint_;                     ///< our lane (Register.lane_endpoint), or ""
  std::unique_ptr<transport::Router> lane_in_;    ///< our ZeroMQ lane (loopback tcp, inproc)
  std::unique_ptr<transport::ShmLaneIn> shm_in_;  ///< our shared-memory lane (ipc sessions)
  std::map<std::string, LaneOut> lanes_out_;      ///< partner -> its lane
  std::vector<LaneOut*> lane_of_;  ///< [interface index] the lane its vectors leave on
  std::string lane_bytes_;         ///< the last message from the shared-memory lane (reused)
  std::deque<wire::Envelope> pending_;
  std::vector<std::int64_t> checkpoints_;  ///< instants of our complete checkpoints (Register)
  cosim::Tick checkpoint_every_ = 0;       ///< the coordinator's interval, ticks (0: none)
  cosim::Tick next_checkpoint_ = 0;
  double cpu_before_ = 0.0;
  std::int64_t injected_fault_cycle_ =
      -1;  ///< CRASHLINK_INJECT_INTERNAL_ERROR's cycle here  ///< CPU of the runs before the
           ///< checkpoint restarted from
};

}  // namespace

DaemonResult run_daemon(const DaemonOptions& options) {
  return Daemon(options).run();
}

}  // namespace crashlink::daemon
