#include "apps/launcher.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <optional>
#include <thread>

#include "apps/stop_signal.h"
#include "coordinator/coordinator_run.h"
#include "core/errors.h"
#include "solver/daemon/daemon.h"
#include "solver/run/progress.h"

namespace crashlink::apps {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

std::string PieceOutcome::describe() const {
  if (signal != 0) {
    return fmt::format("{} was killed by signal {} ({}){}", name, signal, strsignal(signal),
                       killed_by_launcher ? ", by the launcher after the others had stopped" : "");
  }
  if (exit_code < 0) return fmt::format("{} did not start", name);
  if (exit_code == 0) return fmt::format("{} finished", name);
  return fmt::format("{} exited with code {}{}", name, exit_code,
                     message.empty() ? std::string() : ": " + message);
}

bool LaunchResult::ok() const {
  for (const auto& p : pieces) {
    if (!p.ok()) return false;
  }
  return !pieces.empty();
}

namespace {

double seconds(const timeval& t) {
  return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
}

fs::path own_directory() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw InputError(
        "cannot read /proc/self/exe to find crashlink-solver and "
        "crashlink-coordinator beside this executable: " +
        ec.message());
  return self.parent_path();
}

fs::path sibling(const std::string& name) {
  const fs::path p = own_directory() / name;
  if (access(p.c_str(), X_OK) != 0) {
    throw InputError(
        fmt::format("{} not found or not executable; build it (it belongs next to "
                    "crashlink: cmake --build BUILD --target {})",
                    p.string(), name));
  }
  return p;
}

/// fork + exec; the child dies with the launcher. Returns the pid.
pid_t spawn(const fs::path& exe, const std::vector<std::string>& args) {
  std::vector<std::string> all{exe.string()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw Error(fmt::format("fork failed: {}", std::strerror(errno)));
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);  // the launcher died before prctl
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    execv(argv[0], argv.data());
    std::fprintf(stderr, "crashlink: cannot execute %s: %s\n", argv[0], std::strerror(errno));
    _exit(127);
  }
  return pid;
}

std::string ipc_endpoint(const fs::path& out) {
  const std::string path = (out / "coordinator.sock").string();
  if (path.size() <= transport::kMaxIpcPath) {
    fs::remove(path);
    return "ipc://" + path;
  }
  return transport::local_endpoint(transport::Scheme::ipc, "run");
}

class ProcessRun {
 public:
  ProcessRun(const LaunchOptions& o, const std::vector<std::string>& domains)
      : o_(o), domains_(domains) {}

  LaunchResult run() {
    const auto wall0 = Clock::now();
    const fs::path out = fs::absolute(o_.out_dir);
    fs::create_directories(out);
    const fs::path coordinator_exe = sibling("crashlink-coordinator");
    const fs::path solver_exe = sibling("crashlink-solver");
    const std::string bind =
        o_.scheme == transport::Scheme::tcp ? "tcp://127.0.0.1:*" : ipc_endpoint(out);
    const fs::path endpoint_file = out / "coordinator.endpoint";
    fs::remove(endpoint_file);
    // The coordinator removes both at its end; one that was killed, or a launcher that gives up
    // waiting for it, cannot: removed here on every way out.
    struct RemoveOnExit {
      fs::path file;
      std::string socket;  // the ipc:// endpoint bound, or another scheme's
      ~RemoveOnExit() {
        std::error_code ec;
        fs::remove(file, ec);
        if (socket.rfind("ipc://", 0) == 0 && fs::is_socket(socket.substr(6), ec))
          fs::remove(socket.substr(6), ec);
      }
    } remove_on_exit{endpoint_file, bind};
    const std::string scenario = fs::absolute(o_.scenario).string();

    std::vector<std::string> args{"--bind",
                                  bind,
                                  "--scenario",
                                  scenario,
                                  "--out",
                                  out.string(),
                                  "--mode",
                                  o_.run.common_step ? "split" : "multi",
                                  "--endpoint-file",
                                  endpoint_file.string(),
                                  "--join-timeout-ms",
                                  std::to_string(o_.join_timeout_ms)};
    for (const auto& a : o_.session.arguments()) args.push_back(a);
    if (o_.progress) args.emplace_back("--progress");
    // The run's configuration (coupling/coupling_config.h) as the coordinator's flags.
    args.emplace_back("--coupling");
    args.push_back(o_.run.scheme);
    if (o_.run.checkpoint_interval_s > 0.0) {
      args.emplace_back("--checkpoint-interval");
      args.push_back(fmt::format("{:.17g}", o_.run.checkpoint_interval_s));
    }
    if (o_.run.restart) args.emplace_back("--restart");
    if (!o_.run.lanes) args.emplace_back("--no-lanes");
    if (!o_.run.drift) args.emplace_back("--no-drift");
    if (o_.run.variable_steps) args.emplace_back("--variable-steps");
    add("coordinator", spawn(coordinator_exe, args));

    LaunchResult r;
    r.endpoint = await_endpoint(endpoint_file);
    if (!r.endpoint.empty()) {
      for (std::size_t k = 0; k < domains_.size(); ++k) {
        const auto& d = domains_[k];
        std::vector<std::string> a{"--connect",  r.endpoint, "--domain", d,
                                   "--scenario", scenario,   "--out",    out.string()};
        for (const auto& s : o_.session.arguments()) a.push_back(s);
        a.emplace_back("--step-safety");
        a.push_back(fmt::format("{:.17g}", o_.step_safety));
        a.emplace_back("--coupling");
        a.push_back(o_.run.scheme);
        a.emplace_back("--threads");
        a.push_back(std::to_string(o_.threads_of(k)));
        add(d, spawn(solver_exe, a));
      }
    }
    wait_all();
    r.stopped_on_request = stopped_on_request_;
    for (auto& c : children_) r.pieces.push_back(c.outcome);
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0).count();
    return r;
  }

 private:
  struct Child {
    pid_t pid = -1;
    bool running = false;
    PieceOutcome outcome;
  };

  void add(const std::string& name, pid_t pid) {
    Child c;
    c.pid = pid;
    c.running = true;
    c.outcome.name = name;
    children_.push_back(std::move(c));
  }

  /// Reaps every child that has exited; returns how many are still running.
  std::size_t reap() {
    std::size_t running = 0;
    for (auto& c : children_) {
      if (!c.running) continue;
      int status = 0;
      rusage use{};
      const pid_t got = wait4(c.pid, &status, WNOHANG, &use);
      if (got == c.pid) {
        c.running = false;
        c.outcome.cpu_seconds = seconds(use.ru_utime) + seconds(use.ru_stime);
        if (WIFEXITED(status)) {
          c.outcome.exit_code = WEXITSTATUS(status);
        } else if (WIFSIGNALED(status)) {
          c.outcome.signal = WTERMSIG(status);
        }
        if (!c.outcome.ok() && !first_failure_) first_failure_ = Clock::now();
      } else {
        ++running;
      }
    }
    return running;
  }

  /// The coordinator's endpoint file, or "" if the coordinator exited first.
  std::string await_endpoint(const fs::path& file) {
    const auto deadline = Clock::now() + std::chrono::milliseconds{o_.join_timeout_ms};
    while (Clock::now() < deadline) {
      std::ifstream in(file);
      std::string line;
      if (in && std::getline(in, line) && !line.empty()) return line;
      reap();
      if (!children_.front().running) return {};
      if (stop_flag().load()) return {};  // no daemon started: wait_all stops the coordinator
      std::this_thread::sleep_for(5ms);
    }
    signal_all(SIGKILL);
    throw InputError(fmt::format("the coordinator did not write {} within {} ms", file.string(),
                                 o_.join_timeout_ms));
  }

  void signal_all(int sig) {
    for (auto& c : children_) {
      if (!c.running) continue;
      kill(c.pid, sig);
      c.outcome.killed_by_launcher = true;
    }
  }

  /// Until every child has exited. A failed piece: the others get the peer timeout to notice and
  /// stop on their own, then SIGTERM, then SIGKILL 2 s later. A stop request (SIGINT / SIGTERM to
  /// the launcher): SIGTERM to every piece at once, each stops at its next cycle or poll and
  /// flushes its file; SIGKILL a peer timeout later to a piece that did not (one in the middle of
  /// a large checkpoint finishes it first).
  void wait_all() {
    const auto grace =
        std::chrono::milliseconds{o_.session.peer_timeout_ms + o_.session.heartbeat_ms} + 2s;
    const auto kill_after = std::max<std::chrono::milliseconds>(
        2s, std::chrono::milliseconds{o_.session.peer_timeout_ms});
    std::optional<Clock::time_point> termed;
    while (reap() > 0) {
      const auto now = Clock::now();
      if (stop_flag().load() && !stopped_on_request_) {
        stopped_on_request_ = true;
        if (!termed) {
          signal_all(SIGTERM);
          termed = now;
        }
      }
      if (first_failure_ && !termed && now - *first_failure_ > grace) {
        signal_all(SIGTERM);
        termed = now;
      }
      if (termed && now - *termed > (stopped_on_request_ ? kill_after : 2s)) signal_all(SIGKILL);
      std::this_thread::sleep_for(5ms);
    }
  }

  const LaunchOptions& o_;
  const std::vector<std::string>& domains_;
  std::vector<Child> children_;
  std::optional<Clock::time_point> first_failure_;
  bool stopped_on_request_ = false;
};

LaunchResult run_threads(const LaunchOptions& o, const std::vector<std::string>& domains) {
  const auto wall0 = Clock::now();
  LaunchResult r;
  coordinator::CoordinatorOptions co;
  co.bind = transport::local_endpoint(transport::Scheme::inproc, "run");
  co.scenario = o.scenario;
  co.out_dir = o.out_dir;
  co.run = o.run;
  co.session = o.session.options();
  co.join_timeout = std::chrono::milliseconds{o.join_timeout_ms};
  co.in_process = true;
  co.stop = &stop_flag();
  std::promise<std::string> bound;
  std::atomic<bool> bound_set{false};
  co.on_bound = [&](const std::string& ep) {
    if (!bound_set.exchange(true)) bound.set_value(ep);
  };
  std::optional<run::Progress> bar;
  if (o.progress) {
    co.on_progress = [&](double t_s, double end_s, const std::string& slowest) {
      if (!bar) bar.emplace(stderr, end_s, true);
      bar->update(t_s, "slowest: " + slowest);
    };
  }
  coordinator::CoordinatorResult cr;
  std::thread coordinator([&] {
    cr = coordinator::run_coordinator(co);
    if (!bound_set.exchange(true)) bound.set_value(std::string());
  });
  r.endpoint = bound.get_future().get();
  std::vector<daemon::DaemonResult> dr(domains.size());
  std::vector<std::thread> daemons;
  if (!r.endpoint.empty()) {
    for (std::size_t k = 0; k < domains.size(); ++k) {
      daemons.emplace_back([&, k] {
        daemon::DaemonOptions d;
        d.endpoint = r.endpoint;
        d.domain = domains[k];
        d.scenario = o.scenario;
        d.out_dir = o.out_dir;
        d.session = o.session.options();
        d.in_process = true;
        d.step_safety = o.step_safety;
        d.threads = o.threads_of(k);
        d.coupling = o.run.scheme;
        d.stop = &stop_flag();
        dr[k] = daemon::run_daemon(d);
      });
    }
  }
  for (auto& t : daemons) t.join();
  coordinator.join();
  r.stopped_on_request = stop_flag().load();
  if (bar) bar->finish();
  PieceOutcome c;
  c.name = "coordinator";
  c.exit_code = cr.exit_code;
  c.message = cr.message;
  c.cpu_seconds = cr.cpu_seconds;
  r.pieces.push_back(c);
  for (std::size_t k = 0; k < domains.size(); ++k) {
    PieceOutcome p;
    p.name = domains[k];
    p.exit_code = r.endpoint.empty() ? -1 : dr[k].exit_code;
    p.message = dr[k].message;
    p.cpu_seconds = dr[k].cpu_seconds;
    r.pieces.push_back(p);
  }
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0).count();
  return r;
}

}  // namespace

LaunchResult launch_local(const LaunchOptions& options, const std::vector<std::string>& domains) {
  install_stop_handlers();
  if (options.scheme == transport::Scheme::inproc) return run_threads(options, domains);
  return ProcessRun(options, domains).run();
}

}  // namespace crashlink::apps
