#pragma once
// How an exception ends a daemon (docs/processes.md "Exit codes"): what the daemon alone handles
// (the coordinator's Error, a refused CURVE handshake) before the shared ladder of
// transport/failure.h, and the best-effort report of the failure to the coordinator.
#include <memory>
#include <string>

#include "core/exit_codes.h"
#include "proto/crashlink.pb.h"
#include "transport/daemon_link.h"

namespace crashlink::daemon {

struct DaemonFailure {
  int exit_code = kExitInternal;
  wire::ErrorCode code = wire::ERROR_CODE_INTERNAL;
  bool tell_coordinator = true;  ///< false when the coordinator is the one who stopped us
  std::string text;              ///< "<where>: <what>"
};

/// Call inside a catch block: the exception in flight as a DaemonFailure, its text after `where`.
/// The coordinator's Error: exit 2 when it refused us (version, scenario, domain held), 7 when it
/// stopped the run on request, 5 otherwise; a refused CURVE handshake 2; then
/// transport::current_failure().
DaemonFailure current_daemon_failure(const std::string& where);

/// Reports `f` to the coordinator, best effort (it may be the one that is gone). Before the
/// session exists (`link` empty, `hash` known), a short handshake (at most 2 s) is tried first so
/// that the run stops at once; not for a stop on request, which must end within 1 s.
void tell_coordinator(const DaemonFailure& f, std::unique_ptr<transport::DaemonLink>& link,
                      const std::string& endpoint, const std::string& domain,
                      const std::string& hash, const transport::SessionOptions& session);

}  // namespace crashlink::daemon
