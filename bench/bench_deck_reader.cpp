// Time and memory of the keyword-deck reader (docs/decks.md "Speed"): a generated deck of N
// Belytschko-Tsay shells (a square plate of n x n quads, fixed format, *NODE and *ELEMENT_SHELL
// with a *PART, a section, a material and an end time) read by deck::read_deck in a fresh
// process per size (this program again, --read FILE), which reports its seconds and its peak
// resident memory (VmHWM) against its resident memory before reading (VmRSS).
//
//   bench_deck_reader [--sizes 1e5,3e5,1e6] [--dir DIR (/tmp)] [--keep]
//   bench_deck_reader --read FILE        (the child: one line of figures)
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "solver/deck/model_from_deck.h"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

long status_kib(const char* key) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0)
      return std::strtol(line.c_str() + std::string(key).size() + 1, nullptr, 10);
  return -1;
}

/// A plate of n x n shells, 1 mm quads, in mm-t-s.
void generate(const std::string& path, int n) {
  std::ofstream out(path);
  out << "*KEYWORD\n*NODE\n";
  char buf[128];
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      std::snprintf(buf, sizeof buf, "%8d%16.4f%16.4f%16.4f\n", j * (n + 1) + i + 1, 1.0 * i,
                    1.0 * j, 0.0);
      out << buf;
    }
  out << "*ELEMENT_SHELL\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1;
      std::snprintf(buf, sizeof buf, "%8d%8d%8d%8d%8d%8d\n", j * n + i + 1, 1, a, a + 1, a + n + 2,
                    a + n + 1);
      out << buf;
    }
  out << "*PART\nplate\n         1         1         1\n*SECTION_SHELL\n         1         2"
         "    0.8333         5\n       1.0\n*MAT_ELASTIC\n         1   7.85e-9  210000.0       "
         "0.3\n*CONTROL_TERMINATION\n    1.0e-3\n*END\n";
}

int read_one(const std::string& path) {
  const long base = status_kib("VmRSS");
  const auto t0 = Clock::now();
  const auto r = crashlink::deck::read_deck(path, {"mm-t-s", {}});
  const auto t1 = Clock::now();
  const long hwm = status_kib("VmHWM");
  fmt::print("{} {} {:.3f} {} {}\n", std::filesystem::file_size(path), r.model.element_count(),
             std::chrono::duration<double>(t1 - t0).count(), hwm, base);
  return 0;
}

std::string run_child(const std::string& self, const std::string& file) {
  int pipefd[2];
  if (pipe(pipefd) != 0) return "";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipefd[1], 1);
  posix_spawn_file_actions_addclose(&actions, pipefd[0]);
  std::vector<std::string> args{self, "--read", file};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipefd[1]);
  std::string out;
  char buf[256];
  for (ssize_t k; (k = read(pipefd[0], buf, sizeof buf)) > 0;)
    out.append(buf, static_cast<std::size_t>(k));
  close(pipefd[0]);
  int status = 0;
  if (rc == 0) waitpid(pid, &status, 0);
  return rc == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? out : "";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes{1e5, 3e5, 1e6};
  std::string dir = "/tmp";
  bool keep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--keep") {
      keep = true;
      continue;
    }
    if (i + 1 >= argc) {
      fmt::print(stderr, "bench_deck_reader: {} needs a value\n", flag);
      return 2;
    }
    const std::string value = argv[++i];
    if (flag == "--read") return read_one(value);
    if (flag == "--dir") {
      dir = value;
    } else if (flag == "--sizes") {
      sizes.clear();
      std::stringstream s(value);
      for (std::string item; std::getline(s, item, ',');)
        sizes.push_back(std::strtod(item.c_str(), nullptr));
    } else {
      fmt::print(stderr, "bench_deck_reader: unknown option {}\n", flag);
      return 2;
    }
  }
  const std::string self = std::filesystem::canonical("/proc/self/exe").string();
  fmt::print("{:>10} {:>9} {:>8} {:>10} {:>9} {:>12}\n", "shells", "file MB", "read s",
             "s/M shells", "peak MB", "growth MB");
  for (double s : sizes) {
    const int n = static_cast<int>(std::lround(std::sqrt(s)));
    const std::string file = fmt::format("{}/bench_deck_{}.k", dir, n * n);
    generate(file, n);
    const std::string line = run_child(self, file);
    if (!keep) std::filesystem::remove(file);
    std::stringstream in(line);
    double bytes = 0, elements = 0, seconds = 0, hwm = 0, base = 0;
    if (!(in >> bytes >> elements >> seconds >> hwm >> base)) {
      fmt::print(stderr, "bench_deck_reader: the child failed on {}\n", file);
      return 2;
    }
    fmt::print("{:>10.0f} {:>9.1f} {:>8.3f} {:>10.3f} {:>9.1f} {:>12.1f}\n", elements, bytes / 1e6,
               seconds, seconds / elements * 1e6, hwm / 1024.0, (hwm - base) / 1024.0);
  }
  return 0;
}
