#pragma once
// The ways the coordinator ends a run on purpose (docs/processes.md "Exit codes"): who is to
// blame, the exit code, the Error code every daemon is told, and the message, naming the culprit,
// the values and the fix.
#include <chrono>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"

namespace crashlink::coordinator {

/// A failure that ends the run: who, how, what.
struct Stop {
  int exit_code = 0;
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

/// Domains that did not join (absent) or joined and did not register (silent) in time.
Stop join_timeout_stop(const std::vector<std::string>& absent,
                       const std::vector<std::string>& silent, std::chrono::milliseconds timeout,
                       const std::string& endpoint);
/// Domain `domain` reported an Error: its code decides the exit code.
Stop remote_error_stop(const std::string& domain, const wire::Error& error);
/// Domain `domain` broke the protocol.
Stop protocol_stop(const std::string& domain, const std::string& what);
/// Every process alive, none moving (coupling/stall_watch.h): a deadlocked schedule.
/// latest[k] the instant domain k reported last, finished[k] whether it said Bye.
Stop stuck_stop(const std::vector<std::string>& names, const std::vector<bool>& finished,
                const std::vector<coupling::Tick>& latest, std::int64_t ticks_per_second,
                std::chrono::duration<double> still_for);
/// SIGINT / SIGTERM, or the launcher's stop flag.
Stop requested_stop();

}  // namespace crashlink::coordinator
