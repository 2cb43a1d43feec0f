#include "solver/daemon/daemon_failure.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <exception>

#include "core/exit_codes.h"
#include "transport/curve_errors.h"
#include "transport/errors.h"
#include "transport/failure.h"
#include "transport/session.h"

namespace crashlink::daemon {

DaemonFailure current_daemon_failure(const std::string& where) {
  try {
    throw;
  } catch (const transport::RemoteError& e) {
    const bool refused = e.code() == wire::ERROR_CODE_VERSION_MISMATCH ||
                         e.code() == wire::ERROR_CODE_SCENARIO_MISMATCH ||
                         e.code() == wire::ERROR_CODE_DOMAIN_HELD;
    const int exit_code = refused                                ? kExitInput
                          : e.code() == wire::ERROR_CODE_STOPPED ? kExitStopped
                                                                 : kExitPeer;
    return {exit_code, e.code(), false,
            fmt::format("{}: {} by the coordinator: {}", where, refused ? "refused" : "stopped",
                        e.what())};
  } catch (const transport::CurveRefusedError& e) {
    // Refused by the coordinator's CURVE check: a second handshake would be refused too.
    return {kExitInput, wire::ERROR_CODE_PROTOCOL, false, fmt::format("{}: {}", where, e.what())};
  } catch (...) {
    const auto f = transport::current_failure();
    return {f.exit_code, f.code, true, fmt::format("{}: {}", where, f.text)};
  }
}

void tell_coordinator(const DaemonFailure& f, std::unique_ptr<transport::DaemonLink>& link,
                      const std::string& endpoint, const std::string& domain,
                      const std::string& hash, const transport::SessionOptions& session) {
  try {
    if (!link && !hash.empty() && f.code != wire::ERROR_CODE_STOPPED) {
      auto quick = session;
      quick.handshake_timeout = std::min(quick.handshake_timeout, std::chrono::milliseconds{2000});
      link = std::make_unique<transport::DaemonLink>(endpoint,
                                                     transport::daemon_hello(domain, hash), quick);
    }
    if (link && link->open()) link->send_error(f.code, f.text);
  } catch (const std::exception&) {
    // Nobody to tell: the exit code and the message on stderr say it.
  }
}

}  // namespace crashlink::daemon
