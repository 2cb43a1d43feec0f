#include "coordinator/coordinator_stops.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/exit_codes.h"
#include "core/log_escape.h"

namespace crashlink::coordinator {

Stop join_timeout_stop(const std::vector<std::string>& absent,
                       const std::vector<std::string>& silent, std::chrono::milliseconds timeout,
                       const std::string& endpoint) {
  auto all = absent;
  all.insert(all.end(), silent.begin(), silent.end());
  return Stop{
      kExitPeer, wire::ERROR_CODE_TIMEOUT, all,
      fmt::format("coordinator: within the join timeout of {:.1f} s, {}{}{}; are their daemons "
                  "started with this scenario and connected to {}?",
                  std::chrono::duration<double>(timeout).count(),
                  absent.empty()
                      ? std::string()
                      : fmt::format("domain(s) '{}' did not join", fmt::join(absent, "', '")),
                  absent.empty() || silent.empty() ? "" : " and ",
                  silent.empty() ? std::string()
                                 : fmt::format("domain(s) '{}' joined but did not register",
                                               fmt::join(silent, "', '")),
                  endpoint)};
}

Stop remote_error_stop(const std::string& domain, const wire::Error& err) {
  const int code = err.code() == wire::ERROR_CODE_NUMERICAL ? kExitNumerical
                   : err.code() == wire::ERROR_CODE_MODEL   ? kExitInput
                   : err.code() == wire::ERROR_CODE_STOPPED ? kExitStopped
                   : err.code() == wire::ERROR_CODE_IO      ? kExitIo
                                                            : kExitPeer;
  return Stop{code,
              err.code(),
              {domain},
              fmt::format("coordinator: domain '{}' failed ({}): {}", domain,
                          wire::ErrorCode_Name(err.code()),
                          core::log_escape(err.message(), core::kLogTextBytes))};
}

Stop protocol_stop(const std::string& domain, const std::string& what) {
  return Stop{kExitPeer,
              wire::ERROR_CODE_PROTOCOL,
              {domain},
              fmt::format("coordinator: protocol error by domain '{}': {}", domain, what)};
}

Stop stuck_stop(const std::vector<std::string>& names, const std::vector<bool>& finished,
                const std::vector<coupling::Tick>& latest, std::int64_t ticks_per_second,
                std::chrono::duration<double> still_for) {
  std::vector<std::string> where;
  for (std::size_t k = 0; k < names.size(); ++k)
    where.push_back(fmt::format(
        "'{}' {} t = {:.6e} s", names[k], finished[k] ? "finished, last reported" : "last reported",
        static_cast<double>(latest[k]) / static_cast<double>(ticks_per_second)));
  return Stop{kExitInternal,
              wire::ERROR_CODE_INTERNAL,
              {},
              fmt::format("coordinator: the run is stuck: every process is alive but no domain "
                          "has moved for {:.1f} s ({}). The domains wait for each other: an "
                          "internal error of the schedule; please report it with the scenario",
                          still_for.count(), fmt::join(where, ", "))};
}

Stop requested_stop() {
  return Stop{kExitStopped,
              wire::ERROR_CODE_STOPPED,
              {},
              "coordinator: stopped on request (signal or launcher)"};
}

}  // namespace crashlink::coordinator
