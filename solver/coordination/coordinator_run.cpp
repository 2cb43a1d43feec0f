#include "solver/coordination/coordinator_run.h"

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
#include <utility>

#include "coordinator/interface_match.h"
#include "coordinator/layer_router.h"
#include "coordinator/protocol_error.h"
#include "coordinator/stall_watch.h"
#include "solver/coordination/coordinator_checkpoints.h"
#include "solver/coordination/coupling_history.h"
#include "solver/coordination/layer_cut.h"
#include "solver/coordination/paper_cut.h"
#include "solver/coordination/paper_exchange.h"
#include "solver/core/errors.h"
#include "solver/core/log_escape.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "solver/run/checkpoint_store.h"
#include "solver/run/cpu_clock.h"
#include "solver/run/exit_codes.h"
#include "transport/coordinator_link.h"
#include "transport/errors.h"
#include "transport/shm_lane.h"

namespace crashlink::coordination {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::span<const double> view(const google::protobuf::RepeatedField<double>& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

std::string body_name(const wire::Envelope& e) {
  const auto* field = wire::Envelope::descriptor()->FindFieldByNumber(e.body_case());
  return field != nullptr ? field->name() : "empty Envelope";
}

/// A failure that ends the run: who, how, what.
struct Stop {
  int exit_code = run::kExitPeer;
  wire::ErrorCode code = wire::ERROR_CODE_INTERNAL;
  std::vector<std::string> culprits;  ///< the domains to blame (the first is reported)
  std::string text;
};

class StopRun : public std::exception {
 public:
  explicit StopRun(Stop s) : stop_(std::move(s)) {}
  const Stop& stop() const { return stop_; }
  const char* what() const noexcept override { return stop_.text.c_str(); }

 private:
  Stop stop_;
};

class Coordinator {
 public:
  explicit Coordinator(const CoordinatorOptions& o) : o_(o) {}

  CoordinatorResult run() {
    wall0_ = Clock::now();
    cpu0_ = cpu_seconds();
    std::optional<Stop> stop;
    try {
      prepare();
      admit();
      route();
      if (checkpoints_) checkpoints_->prune_all();
    } catch (const StopRun& s) {
      stop = s.stop();
    } catch (const transport::PeerTimeoutError& e) {
      stop = Stop{run::kExitPeer, wire::ERROR_CODE_TIMEOUT,
                  link_ ? link_->dead_peers() : std::vector<std::string>{},
                  fmt::format("coordinator: {}", e.what())};
    } catch (const transport::TransportError& e) {
      stop = Stop{
          run::kExitPeer, wire::ERROR_CODE_INTERNAL, {}, fmt::format("coordinator: {}", e.what())};
    } catch (const NumericalError& e) {
      stop = Stop{run::kExitNumerical,
                  wire::ERROR_CODE_NUMERICAL,
                  {},
                  fmt::format("coordinator: {}", e.what())};
    } catch (const IoError& e) {
      stop = Stop{run::kExitIo,
                  wire::ERROR_CODE_IO,
                  {},
                  fmt::format("coordinator: I/O error: {}", e.what())};
    } catch (const std::filesystem::filesystem_error& e) {
      stop = Stop{run::kExitIo,
                  wire::ERROR_CODE_IO,
                  {},
                  fmt::format("coordinator: I/O error: {}", e.what())};
    } catch (const InputError& e) {
      stop = Stop{run::kExitInput,
                  wire::ERROR_CODE_MODEL,
                  {},
                  fmt::format("coordinator: input error: {}", e.what())};
    } catch (const ModelError& e) {
      stop = Stop{run::kExitInput,
                  wire::ERROR_CODE_MODEL,
                  {},
                  fmt::format("coordinator: model error: {}", e.what())};
    } catch (const std::exception& e) {
      stop = Stop{run::kExitInternal,
                  wire::ERROR_CODE_INTERNAL,
                  {},
                  fmt::format("coordinator: internal error: {}", e.what())};
    }
    CoordinatorResult r;
    if (stop) {
      tell_everyone(*stop);
      r.exit_code = stop->exit_code;
      r.message = stop->text;
      r.culprit = stop->culprits.empty() ? std::string() : stop->culprits.front();
    }
    remove_lane_files();
    remove_session_files();
    r.cpu_seconds = run_cpu_seconds();
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0_).count();
    close_history(r);
    r.endpoint = link_ ? link_->endpoint() : std::string();
    r.messages_forwarded = router_ ? router_->forwarded() : 0;
    r.lanes = lanes_;
    r.reports = reports_;
    r.notices = notices_;
    r.checkpoint_interval_ticks = checkpoints_ ? checkpoints_->every() : 0;
    r.restarted_from_ticks = checkpoints_ ? checkpoints_->restarted_from() : -1;
    r.domains = outcomes_;
    return r;
  }

 private:
  double cpu_seconds() const {
    return o_.in_process ? thread_cpu_seconds() : run::process_cpu_seconds();
  }
  /// CPU of this run, plus that of the run(s) before the checkpoint it restarted from.
  double run_cpu_seconds() const { return cpu_before_ + cpu_seconds() - cpu0_; }

  void prepare() {
    auto read = io::read_scenario_with_hash(o_.scenario);  // one parse for both
    const std::string hash = std::move(read.hash);
    model_ = std::make_unique<model::Model>(std::move(read.model));
    const auto dec = partition::decompose(
        *model_, o_.paper ? partition::Scheme::Paper : partition::Scheme::Layer);
    if (!o_.drift && !o_.paper)
      throw InputError(
          "--no-drift: a `paper` option; `layer` has no drift correction (add --coupling paper, "
          "or drop the option)");
    if (o_.paper) {
      if (o_.checkpoint_interval_s > 0.0 || o_.restart)
        throw InputError(
            "--coupling paper: checkpoints and --restart are features of `layer` "
            "runs; run `paper` without them");
      paper_cut_ = std::make_unique<PaperCut>(paper_cut(*model_, dec));
      cut_ = paper_cut_->cut;
    } else {
      cut_ = layer_cut(*model_, dec);
    }
    outcomes_.resize(cut_.names.size());
    for (std::size_t k = 0; k < cut_.names.size(); ++k) outcomes_[k].name = cut_.names[k];
    regs_.resize(cut_.names.size());
    registered_.assign(cut_.names.size(), false);

    std::filesystem::create_directories(o_.out_dir);
    hash_ = hash;
    if (!o_.restart) run::remove_checkpoints(o_.out_dir, CoordinatorCheckpoints::kSelf);
    history_ = std::make_unique<CouplingHistory>(
        (std::filesystem::path(o_.out_dir) / "coordinator.h5").string(), cut_,
        o_.paper ? "paper" : "layer");

    transport::CoordinatorConfig config;
    config.scenario_hash = hash;
    config.domains = cut_.names;
    config.ticks_per_second = o_.ticks_per_second;
    config.options = o_.session;
    link_ = std::make_unique<transport::CoordinatorLink>(o_.bind, config);
    reclaim_orphan_lanes();
    if (!o_.endpoint_file.empty())
      write_file_atomically(o_.endpoint_file, link_->endpoint() + "\n");
    if (o_.log != nullptr) {
      std::fprintf(o_.log, "crashlink-coordinator: listening on %s for %zu domains ('%s')\n",
                   link_->endpoint().c_str(), cut_.names.size(),
                   fmt::format("{}", fmt::join(cut_.names, "', '")).c_str());
      std::fflush(o_.log);
    }
    if (o_.on_bound) o_.on_bound(link_->endpoint());
  }

  int index_of(const std::string& domain) const {
    const auto it = std::find(cut_.names.begin(), cut_.names.end(), domain);
    return it == cut_.names.end() ? -1 : static_cast<int>(it - cut_.names.begin());
  }

  /// Every domain joins and registers; then the Setups.
  void admit() {
    const auto deadline = Clock::now() + o_.join_timeout;
    std::size_t count = 0;
    while (count < cut_.names.size()) {
      check_stop_requested();
      const auto now = Clock::now();
      if (now >= deadline) {
        std::vector<std::string> absent, silent;
        for (std::size_t k = 0; k < cut_.names.size(); ++k) {
          if (registered_[k]) continue;
          (link_->joined(cut_.names[k]) ? silent : absent).push_back(cut_.names[k]);
        }
        auto all = absent;
        all.insert(all.end(), silent.begin(), silent.end());
        throw StopRun(Stop{
            run::kExitPeer, wire::ERROR_CODE_TIMEOUT, all,
            fmt::format("coordinator: within the join timeout of {:.1f} s, {}{}{}; are their "
                        "daemons started with this scenario and connected to {}?",
                        std::chrono::duration<double>(o_.join_timeout).count(),
                        absent.empty()
                            ? std::string()
                            : fmt::format("domain(s) '{}' did not join", fmt::join(absent, "', '")),
                        absent.empty() || silent.empty() ? "" : " and ",
                        silent.empty() ? std::string()
                                       : fmt::format("domain(s) '{}' joined but did not register",
                                                     fmt::join(silent, "', '")),
                        link_->endpoint())});
      }
      auto in = link_->poll(std::min<std::chrono::milliseconds>(
          100ms, std::chrono::ceil<std::chrono::milliseconds>(deadline - now)));
      drop_silent_unregistered();
      log_notices();
      link_->check_alive();
      if (!in) continue;
      const int k = index_of(in->domain);
      const auto& e = in->envelope;
      if (e.has_error()) remote_error(*in);
      if (!e.has_registration() || registered_[static_cast<std::size_t>(k)]) {
        protocol_stop(in->domain, fmt::format("domain '{}' sent a {} before its Setup; expected "
                                              "one Register",
                                              in->domain, body_name(e)));
      }
      try {
        if (paper_cut_) {
          check_paper_register(*paper_cut_, k, e.registration());
        } else {
          check_register(cut_, k, e.registration());
        }
      } catch (const ModelError& x) {
        throw StopRun(Stop{run::kExitInput,
                           wire::ERROR_CODE_MODEL,
                           {in->domain},
                           fmt::format("coordinator: {}", x.what())});
      }
      regs_[static_cast<std::size_t>(k)] = e.registration();
      registered_[static_cast<std::size_t>(k)] = true;
      link_->seal(in->domain);  // the run counts on this session: no second daemon for it
      ++count;
    }
    coordinator::InterfaceTable table;
    try {
      if (paper_cut_) {
        table = match_paper(*paper_cut_, regs_);
      } else {
        match_sides(cut_, regs_);
      }
    } catch (const coordinator::InterfaceError& x) {
      throw StopRun(Stop{run::kExitInput, wire::ERROR_CODE_MODEL, x.domains(),
                         fmt::format("coordinator: {}", x.what())});
    }
    const auto plan = plan_steps(cut_, regs_, o_.common_step);
    wire::Options options;
    options.set_heartbeat_interval_ms(
        static_cast<std::uint32_t>(o_.session.heartbeat_interval.count()));
    options.set_peer_timeout_ms(static_cast<std::uint32_t>(o_.session.peer_timeout.count()));
    latest_.assign(cut_.names.size(), 0);
    if (paper_cut_) {
      start_paper(table, plan, options);
      return;
    }
    std::vector<coordinator::LayerRoute> routes;
    for (const auto& c : cut_.interfaces) {
      const auto H = plan.step[static_cast<std::size_t>(c.coarse)];
      routes.push_back({c.fine, c.coarse, c.j_node_ids.size(), H,
                        static_cast<double>(H) / static_cast<double>(o_.ticks_per_second)});
    }
    router_ = std::make_unique<coordinator::LayerRouter>(std::move(routes), cut_.names);
    router_->set_variable_steps(o_.variable_steps);
    lanes_ = o_.lanes && std::all_of(regs_.begin(), regs_.end(), [](const wire::Register& r) {
               return !r.lane_endpoint().empty();
             });
    checkpoints_ = std::make_unique<CoordinatorCheckpoints>(o_, cut_, hash_);
    options.set_checkpoint_interval_ticks(checkpoints_->plan(plan.step));
    if (o_.restart) {
      const auto T = checkpoints_->choose_restart(regs_, router_->size() > 0);
      cpu_before_ = checkpoints_->restore(T, *router_, *history_);
      if (router_->size() > 0) std::fill(latest_.begin(), latest_.end(), T);
    }
    const coordinator::Tick restart_from = checkpoints_->restarted_from();
    for (std::size_t k = 0; k < cut_.names.size(); ++k) {
      outcomes_[k].step_ticks = plan.step[k];
      auto setup = setup_message(cut_, plan, static_cast<int>(k), o_.common_step, options,
                                 o_.ticks_per_second);
      setup.mutable_setup()->set_variable_steps(o_.variable_steps);
      if (restart_from >= 0) {
        setup.mutable_setup()->set_restart(true);
        setup.mutable_setup()->set_restart_ticks(restart_from);
      }
      if (lanes_) add_lanes(static_cast<int>(k), *setup.mutable_setup());
      link_->send(cut_.names[k], setup);
    }
    if (o_.log != nullptr) {
      std::string steps;
      for (std::size_t k = 0; k < cut_.names.size(); ++k) {
        steps += fmt::format(
            "{}{} {:.4e} s", k == 0 ? "" : ", ", cut_.names[k],
            static_cast<double>(plan.step[k]) / static_cast<double>(o_.ticks_per_second));
      }
      std::fprintf(
          o_.log, "crashlink-coordinator: %s run, %s: %s; layer vectors %s\n",
          o_.common_step ? "split" : "multi",
          o_.variable_steps ? "variable steps (each its own proposal), planned first" : "steps",
          steps.c_str(), lanes_ ? "daemon to daemon (lanes)" : "through the coordinator");
      std::fflush(o_.log);
    }
  }

  /// Before the run: a domain that said Hello but has been silent for the peer timeout without
  /// registering (a daemon that died or hangs during its start, or a peer that only said Hello)
  /// loses its session and the domain waits for a daemon again, up to the join timeout; the
  /// waiting coordinator goes on. A registered domain that goes silent stops the run
  /// (check_alive()): the others' Setups depend on it.
  void drop_silent_unregistered() {
    for (const auto& d : link_->dead_peers()) {
      const int k = index_of(d);
      if (k < 0 || registered_[static_cast<std::size_t>(k)]) continue;
      link_->drop(
          d, wire::ERROR_CODE_TIMEOUT,
          fmt::format("domain '{}' said Hello and then nothing for {:.1f} s (peer timeout), no "
                      "Register: its session is dropped and the domain waits for a daemon until "
                      "the join timeout ({:.1f} s after the start)",
                      d, std::chrono::duration<double>(o_.session.peer_timeout).count(),
                      std::chrono::duration<double>(o_.join_timeout).count()));
    }
  }

  /// `paper`: the exchange, the Setups (summed masses, roles, step) and the log line.
  void start_paper(const coordinator::InterfaceTable& table, const coordinator::StepPlan& plan,
                   wire::Options options) {
    options.set_drift_correction(o_.drift);
    exchange_ = std::make_unique<PaperExchange>(
        *paper_cut_, table, plan.step,
        o_.drift ? coordinator::paper::Drift::on : coordinator::paper::Drift::off, o_.guard_rise,
        o_.ticks_per_second,
        !o_.variable_steps ? PaperExchange::Steps::fixed
        : o_.common_step   ? PaperExchange::Steps::variable_common
                           : PaperExchange::Steps::variable_own);
    std::string steps;
    for (std::size_t k = 0; k < cut_.names.size(); ++k) {
      outcomes_[k].step_ticks = plan.step[k];
      link_->send(cut_.names[k],
                  paper_setup(*paper_cut_, table, plan, static_cast<int>(k), o_.common_step,
                              options, o_.ticks_per_second, exchange_->end_ticks()));
      steps +=
          fmt::format("{}{} {:.4e} s", k == 0 ? "" : ", ", cut_.names[k],
                      static_cast<double>(plan.step[k]) / static_cast<double>(o_.ticks_per_second));
    }
    if (o_.log != nullptr) {
      std::fprintf(
          o_.log,
          "crashlink-coordinator: %s run, scheme `paper` (drift correction [11] %s, "
          "%zu coupled nodes), %s: %s\n",
          o_.common_step ? "split" : "multi", o_.drift ? "on" : "off", table.nodes.size(),
          o_.variable_steps ? "variable steps (each state's proposal), initially" : "steps",
          steps.c_str());
      std::fflush(o_.log);
    }
  }

  /// `paper`: domain k's free state in, the corrections it allows out, the rows it completes.
  void free_state(int k, const wire::FreeState& f) {
    try {
      exchange_->submit(k, f);
      latest_[static_cast<std::size_t>(k)] = f.time_ticks();
      while (auto c = exchange_->next())
        link_->send(cut_.names[static_cast<std::size_t>(c->first)], c->second);
    } catch (...) {
      history_->append(exchange_->take_rows(), o_.ticks_per_second);  // what was complete
      throw;
    }
    history_->append(exchange_->take_rows(), o_.ticks_per_second);
  }

  void route() {
    std::size_t done = 0;
    const double end_s = cut_.end_time_s;
    coordinator::StallWatch stall(2 * o_.session.peer_timeout);
    while (done < cut_.names.size()) {
      check_stop_requested();
      auto in = link_->poll(100ms);
      log_notices();
      if (in) {
        const int k = index_of(in->domain);
        auto& e = in->envelope;
        try {
          if (exchange_ &&
              (e.has_layer_report() || e.has_layer_force() || e.has_layer_displacement())) {
            protocol_stop(in->domain, fmt::format("domain '{}' sent a {} in a `paper` run",
                                                  in->domain, body_name(e)));
          } else if (e.has_free_state() && exchange_) {
            free_state(k, e.free_state());
          } else if (e.has_layer_report()) {
            report(k, e.layer_report());
          } else if (e.has_layer_force()) {
            const auto& f = e.layer_force();
            auto routed = router_->force(k, f.interface_index(), f.time_ticks(), view(f.forces_n()),
                                         view(f.moments_n_m()));
            forward(routed.to, *in);
          } else if (e.has_layer_displacement()) {
            const auto& d = e.layer_displacement();
            auto routed = router_->displacement(k, d.interface_index(), d.time_ticks(),
                                                view(d.displacements_m()),
                                                view(d.angular_velocities_rad_s()));
            forward(routed.to, *in);
          } else if (e.has_bye()) {
            if (exchange_) {
              // A Bye before the stop would leave its partners waiting for its states.
              if (!exchange_->finished(k))
                protocol_stop(in->domain,
                              fmt::format("domain '{}' said Bye ({}) at tick {} before the end "
                                          "of the `paper` run",
                                          in->domain, core::log_escape(e.bye().reason()),
                                          exchange_->latest(k)));
              exchange_->final_energy(k, e.bye().report().energy(), e.bye().report().time_ticks());
            }
            bye(k, e.bye());
            ++done;
          } else if (e.has_error()) {
            remote_error(*in);
          } else {
            protocol_stop(in->domain, fmt::format("domain '{}' sent a {} during the run",
                                                  in->domain, body_name(e)));
          }
        } catch (const coordinator::ProtocolError& x) {
          protocol_stop(in->domain, x.what());
        }
        if (o_.on_progress) {
          const int slow = slowest();
          const double t = slow < 0 ? end_s
                                    : static_cast<double>(latest_[static_cast<std::size_t>(slow)]) /
                                          static_cast<double>(o_.ticks_per_second);
          o_.on_progress(t, end_s,
                         slow < 0 ? std::string() : cut_.names[static_cast<std::size_t>(slow)]);
        }
      }
      link_->check_alive();
      if (stall.stuck(latest_, done, coordinator::StallWatch::Clock::now())) stuck(stall);
    }
  }

  /// Every process alive, none moving (coordinator/stall_watch.h): a deadlocked schedule.
  [[noreturn]] void stuck(const coordinator::StallWatch& stall) {
    std::vector<std::string> where;
    for (std::size_t k = 0; k < cut_.names.size(); ++k)
      where.push_back(
          fmt::format("'{}' {} t = {:.6e} s", cut_.names[k],
                      outcomes_[k].finished ? "finished, last reported" : "last reported",
                      static_cast<double>(latest_[k]) / static_cast<double>(o_.ticks_per_second)));
    throw StopRun(Stop{
        run::kExitInternal,
        wire::ERROR_CODE_INTERNAL,
        {},
        fmt::format("coordinator: the run is stuck: every process is alive but no domain has "
                    "moved for {:.1f} s ({}). The domains wait for each other: an internal error "
                    "of the schedule; please report it with the scenario",
                    std::chrono::duration<double>(stall.still_for()).count(),
                    fmt::join(where, ", "))});
  }

  /// A LayerReport from domain k: its progress and, from a fine side, history rows, each checked
  /// (LayerRouter::rows: k's fine-side interface, the next owner instants in order, sizes).
  void report(int k, const wire::LayerReport& rep) {
    ++reports_;
    const auto ku = static_cast<std::size_t>(k);
    if (rep.time_ticks() < latest_[ku]) {
      throw coordinator::ProtocolError(
          fmt::format("domain '{}' reported t = {} ticks after t = {} ticks (time goes forward)",
                      cut_.names[ku], rep.time_ticks(), latest_[ku]));
    }
    latest_[ku] = rep.time_ticks();
    // At the end time the daemon writes its results before its Bye: a longer silence is allowed
    // (CoordinatorLink::allow_silence), 10 peer timeouts and at least 30 s.
    if (static_cast<double>(rep.time_ticks()) >=
        cut_.end_time_s * static_cast<double>(o_.ticks_per_second) - 0.5)
      link_->allow_silence(cut_.names[ku],
                           std::max<std::chrono::milliseconds>(10 * o_.session.peer_timeout,
                                                               std::chrono::seconds{30}));
    for (const auto& rows : rep.rows()) {
      const auto i = rows.interface_index();
      const auto samples = router_->rows(
          k, i, {rows.time_ticks().data(), static_cast<std::size_t>(rows.time_ticks_size())},
          view(rows.force_n()), view(rows.link_work_j()));
      history_->append(i, samples, o_.ticks_per_second);
      if (!samples.empty()) checkpoints_->rows_reached(i, samples.back().time);
    }
    if (rep.checkpoint()) checkpoints_->announced(rep.time_ticks());
    checkpoints_->write_when_complete(*router_, *history_, run_cpu_seconds());
  }

  /// The shared-memory lane files that runs killed before their clean-up left in /dev/shm (a
  /// SIGKILLed launcher takes its pieces with it: nobody removed their 4 MB rings).
  void reclaim_orphan_lanes() const {
    if (o_.bind.rfind("ipc://", 0) != 0) return;
    const std::size_t n = transport::reclaim_orphan_shm_files("/dev/shm", "crashlink-");
    if (n > 0 && o_.log != nullptr) {
      std::fprintf(o_.log,
                   "crashlink-coordinator: removed %zu shared-memory lane file(s) in /dev/shm "
                   "left by runs that were killed\n",
                   n);
      std::fflush(o_.log);
    }
  }

  /// What the run made beside its results: the endpoint file, and the ipc socket (ZeroMQ leaves
  /// it). Only the socket this coordinator bound: an ipc:// path, no wildcard.
  void remove_session_files() const {
    std::error_code ec;
    if (!o_.endpoint_file.empty()) std::filesystem::remove(o_.endpoint_file, ec);
    const std::string ipc = "ipc://";
    if (link_ && o_.bind.rfind(ipc, 0) == 0 && o_.bind.find('*') == std::string::npos) {
      const std::string path = o_.bind.substr(ipc.size());
      if (std::filesystem::is_socket(path, ec)) std::filesystem::remove(path, ec);
    }
  }

  /// Shared-memory lanes of daemons that died leave their files behind: remove them.
  void remove_lane_files() const {
    for (std::size_t k = 0; k < regs_.size(); ++k) {
      if (!registered_[k]) continue;
      transport::remove_shm_lane_files(regs_[k].lane_endpoint(), cut_.names);
    }
  }

  /// A partner's lane in daemon k's Setup for every domain k shares an interface with.
  void add_lanes(int k, wire::Setup& setup) const {
    std::set<int> partners;
    for (const auto& c : cut_.interfaces) {
      if (c.fine == k) partners.insert(c.coarse);
      if (c.coarse == k) partners.insert(c.fine);
    }
    for (const int p : partners) {
      auto* lane = setup.add_lanes();
      lane->set_domain(cut_.names[static_cast<std::size_t>(p)]);
      lane->set_endpoint(regs_[static_cast<std::size_t>(p)].lane_endpoint());
      lane->set_public_key(regs_[static_cast<std::size_t>(p)].lane_public_key());
    }
  }

  /// The unfinished domain furthest behind (by its latest report), or -1.
  int slowest() const {
    int slow = -1;
    for (std::size_t k = 0; k < cut_.names.size(); ++k) {
      if (outcomes_[k].finished) continue;
      const int ki = static_cast<int>(k);
      if (slow < 0 || latest_[k] < latest_[static_cast<std::size_t>(slow)]) slow = ki;
    }
    return slow;
  }

  /// The message's bytes as they came (CoordinatorLink::forward: no re-serialisation, no copy).
  void forward(int to, transport::Incoming& in) {
    const auto& name = cut_.names[static_cast<std::size_t>(to)];
    if (outcomes_[static_cast<std::size_t>(to)].finished) return;  // nothing left to use it for
    link_->forward(name, in);
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

  [[noreturn]] void remote_error(const transport::Incoming& in) {
    const auto& err = in.envelope.error();
    const std::string& domain = in.domain;  // the session's (CoordinatorLink::poll)
    const int code = err.code() == wire::ERROR_CODE_NUMERICAL ? run::kExitNumerical
                     : err.code() == wire::ERROR_CODE_MODEL   ? run::kExitInput
                     : err.code() == wire::ERROR_CODE_STOPPED ? run::kExitStopped
                     : err.code() == wire::ERROR_CODE_IO      ? run::kExitIo
                                                              : run::kExitPeer;
    throw StopRun(Stop{code,
                       err.code(),
                       {in.domain},
                       fmt::format("coordinator: domain '{}' failed ({}): {}", domain,
                                   wire::ErrorCode_Name(err.code()),
                                   core::log_escape(err.message(), core::kLogTextBytes))});
  }

  [[noreturn]] void protocol_stop(const std::string& domain, const std::string& what) {
    throw StopRun(
        Stop{run::kExitPeer,
             wire::ERROR_CODE_PROTOCOL,
             {domain},
             fmt::format("coordinator: protocol error by domain '{}': {}", domain, what)});
  }

  void check_stop_requested() const {
    if (o_.stop != nullptr && o_.stop->load()) {
      throw StopRun(Stop{run::kExitStopped,
                         wire::ERROR_CODE_STOPPED,
                         {},
                         "coordinator: stopped on request (signal or launcher)"});
    }
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
    for (const auto& name : cut_.names) {
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
  LayerCut cut_;
  std::vector<wire::Register> regs_;
  std::vector<bool> registered_;
  std::vector<DomainOutcome> outcomes_;
  std::unique_ptr<CouplingHistory> history_;
  std::unique_ptr<coordinator::LayerRouter> router_;
  std::unique_ptr<PaperCut> paper_cut_;      ///< `paper` only
  std::unique_ptr<PaperExchange> exchange_;  ///< `paper` only
  std::unique_ptr<transport::CoordinatorLink> link_;
  std::int64_t notices_ = 0;
  std::set<std::string> logged_;
  std::string hash_;
  std::unique_ptr<CoordinatorCheckpoints> checkpoints_;  ///< `layer`, once the steps are planned
  double cpu_before_ = 0.0;  ///< CPU of the run(s) before the checkpoint restarted from
  std::vector<coordinator::Tick> latest_;  ///< [daemons] the instant of the latest report
  bool lanes_ = false;
  std::int64_t reports_ = 0;
};

}  // namespace

CoordinatorResult run_coordinator(const CoordinatorOptions& options) {
  return Coordinator(options).run();
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = fmt::format("{}.tmp{}", path, static_cast<long>(::getpid()));
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw InputError(fmt::format("cannot write {}", tmp));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(fmt::format("cannot rename {} to {}: {}", tmp, path, ec.message()));
}

}  // namespace crashlink::coordination
