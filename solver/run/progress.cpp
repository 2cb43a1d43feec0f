#include "solver/run/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace crashlink::run {

Progress::Progress(std::FILE* stream, double end_time_s, bool enabled)
    : stream_(stream),
      end_time_s_(end_time_s),
      enabled_(enabled),
      tty_(isatty(fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void Progress::update(double time_s, std::int64_t cycle, double dt_s) {
  if (!enabled_ || (++calls_ & 255) != 0) return;
  char detail[96];
  std::snprintf(detail, sizeof detail, "cycle %lld  dt = %.3e s", static_cast<long long>(cycle),
                dt_s);
  show(time_s, detail);
}

void Progress::update(double time_s, const std::string& detail) {
  if (!enabled_ || (++calls_ & 15) != 0) return;
  show(time_s, detail.c_str());
}

void Progress::show(double time_s, const char* detail) {
  const auto now = std::chrono::steady_clock::now();
  const double frac = std::clamp(time_s / end_time_s_, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = frac > 0.0 ? elapsed * (1.0 - frac) / frac : 0.0;
  if (tty_) {
    if (std::chrono::duration<double>(now - last_).count() < 0.25) return;
    last_ = now;
    const int width = 30;
    const int filled = static_cast<int>(frac * width);
    std::fprintf(stream_, "\r[%.*s%*s] %5.1f %%  t = %.4e s  %s  ETA %.0f s ", filled,
                 "##############################", width - filled, "", 100.0 * frac, time_s, detail,
                 eta);
    std::fflush(stream_);
  } else if (frac * 10.0 >= next_decile_) {
    next_decile_ = static_cast<int>(frac * 10.0) + 1;
    std::fprintf(stream_, "progress %3.0f %%  t = %.4e s  %s  elapsed %.1f s\n", 100.0 * frac,
                 time_s, detail, elapsed);
    std::fflush(stream_);
  }
}

void Progress::finish() {
  if (enabled_ && tty_) std::fprintf(stream_, "\n");
}

}  // namespace crashlink::run
