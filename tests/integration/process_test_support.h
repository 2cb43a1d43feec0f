#pragma once
// Shared by the multi-process tests (layer_processes_test, process_failure_test,
// process_handshake_test): scenario files for a two-domain bar and a shell plate cut along a
// line, child processes with their output captured (the built crashlink, crashlink-solver and
// crashlink-coordinator under CRASHLINK_BINARY_DIR), and the last field state of a result file.
// Every wait is bounded; readiness is read from the processes' output, not slept for.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "transport/endpoint.h"

namespace crashlink::transport {
inline void PrintTo(Scheme scheme, std::ostream* os) {
  *os << scheme_name(scheme);
}
}  // namespace crashlink::transport

namespace crashlink::proc_test {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

inline std::string bin(const std::string& name) {
  return std::string(CRASHLINK_BINARY_DIR) + "/apps/" + name;
}

inline std::string scheme_test_name(const ::testing::TestParamInfo<transport::Scheme>& info) {
  return std::string(transport::scheme_name(info.param));
}

/// A fresh, empty directory for one test (short: ipc socket paths must fit in 107 bytes).
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto d =
      std::filesystem::temp_directory_path() / ("clp-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// Removes a test's directory at the end of the scope unless the test failed (kept to look at).
struct RemoveIfPassed {
  std::filesystem::path dir;
  ~RemoveIfPassed() {
    if (!::testing::Test::HasFailure()) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }
};

inline std::string write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

/// Damages a file as a disk or a hand might: the byte in its middle with one bit flipped.
inline void flip_middle_byte(const std::filesystem::path& file) {
  const auto at = static_cast<std::streamoff>(std::filesystem::file_size(file) / 2);
  std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
  io.seekg(at);
  const char c = static_cast<char>(io.get());
  io.seekp(at);
  io.put(static_cast<char>(c ^ 0x10));
}

/// One part of a steel bar of hexes along x (50 x 50 mm section): [x0, x0 + length] m.
struct BarPart {
  std::string name;
  double x0_m = 0.0;
  double length_m = 0.0;
  int divisions = 1;
};

/// A steel bar of hexes along x made of `parts` end to end (merged on the cuts), the end at
/// x = 0.6 m fixed, a 20 us force pulse on x = 0, one domain per part; `extra` is more YAML (an
/// initial velocity, probes).
inline std::string bar_parts_yaml(const std::string& name, double end_time_s,
                                  const std::vector<BarPart>& parts,
                                  const std::string& extra = {}) {
  std::string y = "name: " + name + "\ncontrols:\n  end_time: " + std::to_string(end_time_s) + R"(
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
)";
  std::string domains = "domains:\n";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& p = parts[i];
    y += "  " + p.name + ":\n    material: steel\n" + (i > 0 ? "    merge_nodes: true\n" : "") +
         "    mesh: {generator: bar, origin: [" + std::to_string(p.x0_m) +
         ", 0.0, 0.0], axis: x, length: " + std::to_string(p.length_m) +
         ", cross_section: [0.05, 0.05], divisions: " + std::to_string(p.divisions) + "}\n";
    domains += "  " + p.name + ": {parts: [" + p.name + "]}\n";
  }
  return y + R"(node_sets:
  far_end: {box: {min: [0.5999, -1.0, -1.0], max: [0.7, 1.0, 1.0]}}
  loaded_end: {box: {min: [-1.0, -1.0, -1.0], max: [1.0e-4, 1.0, 1.0]}}
boundary:
  - {nodes: far_end, fix: all}
loads:
  - nodes: loaded_end
    dof: x
    curve: {t: [0.0, 2.0e-5, 2.1e-5], v: [1.0e+4, 1.0e+4, 0.0]}
)" + extra +
         domains;
}

/// A steel bar of hexes along x: part "fine" [0, 0.2] m (10 mm elements), part "coarse"
/// [0.2, 0.6] m (40 mm), far end fixed, a 20 us force pulse on x = 0, an initial velocity on the
/// coarse part; domains fine / coarse.
inline std::string bar_yaml(double end_time_s, const std::string& name = "bar2") {
  return bar_parts_yaml(name, end_time_s, {{"fine", 0.0, 0.2, 20}, {"coarse", 0.2, 0.4, 10}},
                        R"(initial_velocity:
  - {part: coarse, velocity: [-0.2, 0.1, 0.0]}
probes:
  tip: {node_near: [0.0, 0.025, 0.025]}
)");
}

/// `yaml` (bar_yaml, plate_yaml) for a run meant to be stopped long before its end time (a kill,
/// a network cut): an end time of seconds is then meant, so the reader's plausibility checks
/// (docs/scenario-format.md) are turned off under `controls`.
inline std::string stopped_early(std::string yaml) {
  const auto at = yaml.find("controls:\n");
  if (at == std::string::npos) throw std::runtime_error("no controls section");
  yaml.insert(at + 10, "  plausibility_checks: false\n");
  return yaml;
}

/// A 1 mm steel shell plate 0.2 x 0.1 m cut along x = 0.1: part "left" and part "right" (10 mm
/// elements each, merged on the cut), the right edge clamped, an out-of-plane force pulse on the
/// left edge and an in-plane one; domains left / right.
inline std::string plate_yaml(double end_time_s) {
  return "name: plate2\ncontrols:\n  end_time: " + std::to_string(end_time_s) + R"(
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  left:
    material: steel
    thickness: 1.0e-3
    mesh: {generator: plate, origin: [0.0, 0.0, 0.0], size: [0.1, 0.1], divisions: [10, 10]}
  right:
    material: steel
    thickness: 1.0e-3
    merge_nodes: true
    mesh: {generator: plate, origin: [0.1, 0.0, 0.0], size: [0.1, 0.1], divisions: [10, 10]}
node_sets:
  clamped: {box: {min: [0.1999, -1.0, -1.0], max: [0.3, 1.0, 1.0]}}
  loaded: {box: {min: [-1.0, -1.0, -1.0], max: [1.0e-4, 1.0, 1.0]}}
boundary:
  - {nodes: clamped, fix: all}
loads:
  - nodes: loaded
    dof: z
    curve: {t: [0.0, 5.0e-5, 1.0e-4], v: [0.0, 20.0, 0.0]}
  - nodes: loaded
    dof: x
    curve: {t: [0.0, 2.0e-5, 2.1e-5], v: [500.0, 500.0, 0.0]}
domains:
  left: {parts: [left]}
  right: {parts: [right]}
)";
}

/// The exit code of a wait status; -signal if a signal ended the process.
inline int exit_code(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return -1000;
}

/// A child process; stdout and stderr go to one pipe read by a thread (output()). It runs in
/// `cwd` when given (relative paths in argv then resolve there).
class Child {
 public:
  explicit Child(std::vector<std::string> argv, const std::string& cwd = {}) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(127);
      if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(127);
      dup2(fds[1], 1);
      dup2(fds[1], 2);
      execv(args[0], args.data());
      _exit(127);
    }
    close(fds[1]);
    fd_ = fds[0];
    reader_ = std::thread([this] {
      char buf[4096];
      for (;;) {
        const ssize_t n = read(fd_, buf, sizeof buf);
        if (n <= 0) break;
        std::lock_guard lock(m_);
        out_.append(buf, static_cast<std::size_t>(n));
        cv_.notify_all();
      }
      std::lock_guard lock(m_);
      eof_ = true;
      cv_.notify_all();
    });
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (!status_) {
      kill(pid_, SIGKILL);
      wait(5s);
    }
    if (reader_.joinable()) reader_.join();
    close(fd_);
  }

  pid_t pid() const { return pid_; }
  void signal(int sig) const { kill(pid_, sig); }

  /// The wait status, or nullopt if still running after `timeout`.
  std::optional<int> wait(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!status_) {
      int st = 0;
      const pid_t got = waitpid(pid_, &st, WNOHANG);
      if (got == pid_) {
        status_ = st;
        exited_at_ = Clock::now();
        // The reader thread may not have read the last lines yet: wait for the end of the output
        // (bounded: a grandchild that outlives the child keeps the pipe open). Without this a
        // test read the output of a finished run without its last lines (LayerProcesses.SplitBar*
        // missed "coordinator: CPU", now and then under load).
        std::unique_lock lock(m_);
        cv_.wait_for(lock, 5s, [&] { return eof_; });
        break;
      }
      if (Clock::now() >= deadline) return std::nullopt;
      std::this_thread::sleep_for(2ms);
    }
    return status_;
  }
  /// When wait() saw the exit.
  Clock::time_point exited_at() const { return exited_at_; }

  std::string output() const {
    std::lock_guard lock(m_);
    return out_;
  }
  /// Waits until the output contains `text` (false: timeout or end of output first).
  bool wait_for_output(const std::string& text, std::chrono::milliseconds timeout) {
    std::unique_lock lock(m_);
    return cv_.wait_for(lock, timeout, [&] {
      return out_.find(text) != std::string::npos || eof_;
    }) && out_.find(text) != std::string::npos;
  }
  /// The text between `before` and the next `after` in the output ("" if absent).
  std::string between(const std::string& before, const std::string& after) const {
    const std::string o = output();
    const auto a = o.find(before);
    if (a == std::string::npos) return {};
    const auto b = o.find(after, a + before.size());
    return o.substr(a + before.size(),
                    b == std::string::npos ? std::string::npos : b - a - before.size());
  }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::thread reader_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::string out_;
  bool eof_ = false;
  std::optional<int> status_;
  Clock::time_point exited_at_{};
};

/// Short liveness settings for the tests (the defaults are 500 ms / 5 s).
inline std::vector<std::string> fast_session_args() {
  return {"--heartbeat-ms", "100", "--timeout-ms", "1000", "--handshake-timeout-ms", "10000"};
}

/// The endpoint a coordinator process binds for `scheme` (tcp: ephemeral port, read back).
inline std::string bind_endpoint(transport::Scheme scheme, const std::filesystem::path& dir) {
  return scheme == transport::Scheme::tcp ? "tcp://127.0.0.1:*"
                                          : "ipc://" + (dir / "c.sock").string();
}

/// crashlink-coordinator's command line (no session flags).
inline std::vector<std::string> coordinator_args(const std::string& bind,
                                                 const std::string& scenario,
                                                 const std::filesystem::path& out,
                                                 const std::string& mode) {
  return {bin("crashlink-coordinator"),
          "--bind",
          bind,
          "--scenario",
          scenario,
          "--out",
          out.string(),
          "--mode",
          mode};
}

/// Starts crashlink-coordinator (or `program`) and returns it once it listens; `endpoint` gets the
/// real one.
inline std::unique_ptr<Child> start_coordinator(const std::string& bind,
                                                const std::string& scenario,
                                                const std::filesystem::path& out,
                                                const std::string& mode, std::string& endpoint,
                                                std::vector<std::string> extra = {},
                                                const std::string& program = {}) {
  std::vector<std::string> a = coordinator_args(bind, scenario, out, mode);
  if (!program.empty()) a.front() = program;  // a test's own build of the same program
  for (const auto& s : fast_session_args()) a.push_back(s);
  for (auto& s : extra) a.push_back(std::move(s));
  auto c = std::make_unique<Child>(a);
  EXPECT_TRUE(c->wait_for_output(" for ", 10s)) << c->output();
  endpoint = c->between("listening on ", " for ");
  return c;
}

/// crashlink-solver's command line for one domain (no session flags).
inline std::vector<std::string> solver_args(const std::string& endpoint, const std::string& domain,
                                            const std::string& scenario,
                                            const std::filesystem::path& out) {
  return {bin("crashlink-solver"),
          "--connect",
          endpoint,
          "--domain",
          domain,
          "--scenario",
          scenario,
          "--out",
          out.string()};
}

inline std::unique_ptr<Child> start_solver(const std::string& endpoint, const std::string& domain,
                                           const std::string& scenario,
                                           const std::filesystem::path& out,
                                           std::vector<std::string> extra = {},
                                           const std::string& program = {}) {
  std::vector<std::string> a = solver_args(endpoint, domain, scenario, out);
  if (!program.empty()) a.front() = program;  // a test's own build of the same program
  for (const auto& s : fast_session_args()) a.push_back(s);
  for (auto& s : extra) a.push_back(std::move(s));
  return std::make_unique<Child>(a);
}

/// A whole dataset of doubles ([k] or [k, 3] flattened); empty if absent.
inline std::vector<double> read_doubles(const std::string& h5, const std::string& path) {
  std::vector<double> v;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return v;
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  if (d >= 0) {
    const hid_t sp = H5Dget_space(d);
    v.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp)));
    if (!v.empty() && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      v.clear();
    H5Sclose(sp);
    H5Dclose(d);
  }
  H5Fclose(f);
  return v;
}

/// The last field state of a result file (ours or a daemon's): node ids and displacements.
struct LastState {
  double time_s = -1.0;
  std::vector<std::int64_t> node_ids;  ///< [n]
  std::vector<double> u;               ///< [3n]
  bool ok() const { return time_s >= 0.0 && u.size() == 3 * node_ids.size(); }
};

inline LastState last_state(const std::string& h5) {
  LastState s;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return s;
  auto read_all = [&](const std::string& path, hid_t type, void* out, std::size_t count) {
    const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
    if (d < 0) return false;
    const hid_t sp = H5Dget_space(d);
    const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp));
    const bool ok = n == count && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0;
    H5Sclose(sp);
    H5Dclose(d);
    return ok;
  };
  std::int64_t count = 0;
  const hid_t states = H5Gopen2(f, "/states", H5P_DEFAULT);
  if (states >= 0) {
    const hid_t a = H5Aopen(states, "count", H5P_DEFAULT);
    if (a >= 0) {
      H5Aread(a, H5T_NATIVE_INT64, &count);
      H5Aclose(a);
    }
    H5Gclose(states);
  }
  const hid_t ids = H5Dopen2(f, "/mesh/node_ids", H5P_DEFAULT);
  std::size_t n = 0;
  if (ids >= 0) {
    const hid_t sp = H5Dget_space(ids);
    n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp));
    H5Sclose(sp);
    H5Dclose(ids);
  }
  if (count > 0 && n > 0) {
    const std::string g = "/states/" + std::to_string(count - 1);
    s.node_ids.resize(n);
    s.u.resize(3 * n);
    double t = -1.0;
    const hid_t grp = H5Gopen2(f, g.c_str(), H5P_DEFAULT);
    if (grp >= 0) {
      const hid_t a = H5Aopen(grp, "time", H5P_DEFAULT);
      if (a >= 0) {
        H5Aread(a, H5T_NATIVE_DOUBLE, &t);
        H5Aclose(a);
      }
      H5Gclose(grp);
    }
    if (read_all("/mesh/node_ids", H5T_NATIVE_INT64, s.node_ids.data(), n) &&
        read_all(g + "/displacement", H5T_NATIVE_DOUBLE, s.u.data(), 3 * n)) {
      s.time_s = t;
    }
  }
  H5Fclose(f);
  return s;
}

}  // namespace crashlink::proc_test
