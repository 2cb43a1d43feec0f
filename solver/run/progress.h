#pragma once
// Progress display for long runs: a refreshed line on a terminal, a line every 10 % otherwise.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace crashlink::run {

class Progress {
 public:
  /// `stream` is stderr normally; `end_time_s` the simulated end time.
  Progress(std::FILE* stream, double end_time_s, bool enabled = true);
  /// Cheap to call every cycle: it looks at the clock only every 256 calls.
  void update(double time_s, std::int64_t cycle, double dt_s);
  /// As update(), with `detail` in place of the cycle and step (a coupled run: the slowest
  /// domain's name).
  void update(double time_s, const std::string& detail);
  /// Ends the line on a terminal.
  void finish();

 private:
  void show(double time_s, const char* detail);

  std::FILE* stream_;
  double end_time_s_;
  bool enabled_;
  bool tty_;
  int calls_ = 0;
  int next_decile_ = 1;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace crashlink::run
