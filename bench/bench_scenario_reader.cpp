// Memory and time of the scenario reader on long lists (docs/benchmarks.md "Scenario reader":
// the figures). Generates a scenario per size whose bulk is one list of N values (generate), then
// runs each in a fresh process (this program again, --read FILE: read_one) that does what every
// process of a run does with the scenario; one line per size: input MB, seconds, peak and growth,
// and both per input MB.
//
//   bench_scenario_reader [--sizes 1e6,4e6,13e6] [--list ids|curve] [--style flow|block]
//                         [--dir DIR (/tmp)] [--keep]
//   bench_scenario_reader --read FILE        (the child: one line of figures)
//
// Exit 0, 2 on bad arguments or a failed child.
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "solver/io/scenario_reader.h"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;
namespace io = crashlink::io;

constexpr int kNodes = 1331;  // the 10x10x10 box

struct Options {
  std::vector<double> sizes{1e6, 4e6, 13e6};
  std::string list = "ids";
  std::string style = "flow";
  std::string dir = "/tmp";
  bool keep = false;
  std::string read;  // child mode
};

[[noreturn]] void usage(const std::string& why) {
  fmt::print(stderr,
             "bench_scenario_reader: {}\n"
             "usage: bench_scenario_reader [--sizes 1e6,4e6,13e6] [--list ids|curve]\n"
             "         [--style flow|block] [--dir DIR] [--keep]\n"
             "       bench_scenario_reader --read FILE\n",
             why);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];
    if (flag == "--keep") {
      o.keep = true;
      continue;
    }
    if (i + 1 >= argc) usage(fmt::format("{} needs a value", flag));
    const std::string value = argv[++i];
    if (flag == "--sizes") {
      o.sizes.clear();
      std::stringstream s(value);
      for (std::string item; std::getline(s, item, ',');) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (end == item.c_str() || *end != '\0' || v < 2 || v > 1e9)
          usage(fmt::format("--sizes {}: counts from 2 to 1e9", value));
        o.sizes.push_back(v);
      }
    } else if (flag == "--list" && (value == "ids" || value == "curve")) {
      o.list = value;
    } else if (flag == "--style" && (value == "flow" || value == "block")) {
      o.style = value;
    } else if (flag == "--dir") {
      o.dir = value;
    } else if (flag == "--read") {
      o.read = value;
    } else {
      usage(fmt::format("bad option {} {}", flag, value));
    }
  }
  return o;
}

/// Writes `values` as a YAML list under a key already written, flow (16 a line) or block.
template <class Value>
void write_list(std::ofstream& out, std::size_t n, bool block, const std::string& indent,
                Value value) {
  if (block) {
    out << "\n";
    for (std::size_t k = 0; k < n; ++k) out << indent << "- " << value(k) << "\n";
    return;
  }
  out << " [";
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) out << (k % 16 == 0 ? ",\n" + indent : ", ");
    out << value(k);
  }
  out << "]\n";
}

/// The scenario of size n at path. --list ids: a node set `{nodes: [id, ...]}` of N ids on a
/// 10x10x10 box (1331 nodes, ids spread over them), fixed in z by `boundary`; --list curve: a
/// prescribed velocity whose curve has N/2 points (N numbers, t and v). --style block writes one
/// `- value` per line.
void generate(const std::string& path, std::size_t n, const Options& o) {
  std::ofstream out(path);
  out << "name: reader_bench\n"
         "controls: {end_time: 1.0e-4}\n"
         "materials:\n"
         "  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, "
         "poisson_ratio: 0.3}\n"
         "parts:\n"
         "  block:\n"
         "    material: steel\n"
         "    mesh: {generator: box, size: [0.1, 0.1, 0.1], divisions: [10, 10, 10]}\n";
  const bool block = o.style == "block";
  if (o.list == "ids") {
    out << "node_sets:\n  listed:\n    nodes:";
    write_list(out, n, block, "      ", [](std::size_t k) { return (k * 7919) % kNodes + 1; });
    out << "boundary:\n  - {nodes: listed, fix: [z]}\n";
  } else {
    const std::size_t points = n / 2;
    out << "prescribed_velocity:\n  - nodes: {part: block}\n    dof: x\n    curve:\n      t:";
    write_list(out, points, block, "        ",
               [](std::size_t k) { return fmt::format("{:.6e}", 1e-8 * static_cast<double>(k)); });
    out << "      v:";
    write_list(out, points, block, "        ", [](std::size_t k) {
      return fmt::format("{:.6e}", 0.5 + 1e-3 * static_cast<double>(k % 1000));
    });
  }
  if (!out) usage("cannot write " + path);
}

long status_kib(const char* field) {  // a "VmRSS:   1234 kB" line of /proc/self/status
  std::ifstream in("/proc/self/status");
  const std::string want = std::string(field) + ":";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(want, 0) == 0) return std::atol(line.c_str() + want.size());
  return -1;
}

std::uint64_t fnv(std::uint64_t h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  return h;
}

/// The child: reads like a daemon, io::read_scenario_with_hash (the model and the scenario hash
/// from one parse); one line "bytes seconds hwm_kib base_kib sum hash": its time and its peak
/// resident memory (VmHWM) against its resident memory before reading (VmRSS), and a checksum of
/// what the reader made of the list (the fixed dofs, the curve), so that two builds can be
/// checked to read the same model.
int read_one(const std::string& path) {
  const long base = status_kib("VmRSS");
  const auto t0 = Clock::now();
  const auto [model, hash] = io::read_scenario_with_hash(path);
  const auto t1 = Clock::now();
  const long hwm = status_kib("VmHWM");
  std::uint64_t sum = fnv(14695981039346656037ULL, model.fixed.data(), model.fixed.size());
  for (const auto& pv : model.prescribed_velocities) {
    sum = fnv(sum, pv.velocity.t_s.data(), pv.velocity.t_s.size() * sizeof(double));
    sum = fnv(sum, pv.velocity.value.data(), pv.velocity.value.size() * sizeof(double));
  }
  const double seconds = std::chrono::duration<double>(t1 - t0).count();
  fmt::print("{} {:.3f} {} {} {:016x} {}\n", std::filesystem::file_size(path), seconds, hwm, base,
             sum, hash);
  return 0;
}

/// Runs `--read path` in a fresh process; returns its line.
std::string run_child(const std::string& path) {
  int pipefd[2];
  if (pipe(pipefd) != 0) usage("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipefd[1], 1);
  posix_spawn_file_actions_addclose(&actions, pipefd[0]);
  std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<char*> argv{self.data(), const_cast<char*>("--read"), const_cast<char*>(path.c_str()),
                          nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ) != 0)
    usage("cannot start the child");
  posix_spawn_file_actions_destroy(&actions);
  close(pipefd[1]);
  std::string line;
  char buf[512];
  for (ssize_t got; (got = read(pipefd[0], buf, sizeof buf)) > 0;)
    line.append(buf, static_cast<std::size_t>(got));
  close(pipefd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    usage(fmt::format("the reader failed on {} (status {})", path, status));
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (!o.read.empty()) return read_one(o.read);
  fmt::print(
      "list={} style={}: per process, read_scenario_with_hash (peak = VmHWM, growth = VmHWM - "
      "VmRSS before)\n"
      "{:>10} {:>9} {:>8} {:>9} {:>9} {:>8} {:>8}  {}\n",
      o.list, o.style, "values", "input MB", "seconds", "peak MiB", "growth", "MiB/MB", "s/MB",
      "checksum, hash");
  for (const double size : o.sizes) {
    const auto n = static_cast<std::size_t>(size);
    const std::string path =
        fmt::format("{}/reader_bench_{}_{}_{}.yaml", o.dir, o.list, o.style, n);
    generate(path, n, o);
    std::istringstream line(run_child(path));
    double bytes = 0, seconds = 0, hwm = 0, base = 0;
    std::string sum, hash;
    line >> bytes >> seconds >> hwm >> base >> sum >> hash;
    if (!line) usage("unreadable child line for " + path);
    const double mb = bytes / 1e6;
    fmt::print("{:>10} {:>9.1f} {:>8.2f} {:>9.1f} {:>9.1f} {:>8.2f} {:>8.3f}  {} {}\n", n, mb,
               seconds, hwm / 1024, (hwm - base) / 1024, (hwm - base) / 1024 / mb, seconds / mb,
               sum, hash);
    std::fflush(stdout);
    if (!o.keep) std::filesystem::remove(path);
  }
  return 0;
}
