#include "transport/session.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>

#include "core/log_escape.h"
#include "proto/protocol_version.h"
#include "transport/errors.h"

namespace crashlink::transport {

void SessionOptions::validate(std::string_view endpoint) const {
  if (heartbeat_interval.count() <= 0 || peer_timeout <= heartbeat_interval ||
      handshake_timeout.count() <= 0) {
    throw TransportError(
        std::string(endpoint),
        fmt::format("heartbeat interval {} ms, peer timeout {} ms, handshake timeout {} ms: need "
                    "0 < interval < timeout (a few intervals, e.g. 500 ms and 5000 ms) and a "
                    "positive handshake timeout",
                    heartbeat_interval.count(), peer_timeout.count(), handshake_timeout.count()));
  }
}

wire::Hello daemon_hello(std::string_view domain, std::string_view scenario_hash) {
  wire::Hello h;
  h.set_protocol_version(wire::kProtocolVersion);
  h.set_scenario_hash(std::string(scenario_hash));
  h.set_domain(std::string(domain));
  h.set_role(wire::PEER_ROLE_DAEMON);
  return h;
}

std::optional<wire::Error> check_hello(const wire::Hello& hello, std::string_view scenario_hash,
                                       std::span<const std::string> domains) {
  // The peer's own strings are escaped: they go into the coordinator's log (core::log_escape).
  const std::string domain = core::log_escape(hello.domain());
  auto refuse = [&](wire::ErrorCode code, std::string text) {
    wire::Error e;
    e.set_code(code);
    e.set_message(std::move(text));
    e.set_domain(domain);
    return std::optional<wire::Error>(std::move(e));
  };
  if (hello.role() != wire::PEER_ROLE_DAEMON) {
    return refuse(wire::ERROR_CODE_PROTOCOL,
                  fmt::format("Hello from '{}' with role {}: only daemons (PEER_ROLE_DAEMON) "
                              "connect to a coordinator",
                              domain, wire::PeerRole_Name(hello.role())));
  }
  if (hello.protocol_version() != wire::kProtocolVersion) {
    return refuse(wire::ERROR_CODE_VERSION_MISMATCH,
                  fmt::format("daemon '{}' speaks wire protocol version {}, the coordinator speaks "
                              "version {}; fix: run the same crashlink build (same "
                              "proto/protocol_version.h) for the coordinator and every daemon",
                              domain, hello.protocol_version(), wire::kProtocolVersion));
  }
  if (hello.scenario_hash() != scenario_hash) {
    return refuse(wire::ERROR_CODE_SCENARIO_MISMATCH,
                  fmt::format("daemon '{}' has scenario hash '{}', the coordinator has '{}'; fix: "
                              "start every process with the same scenario file (same content)",
                              domain, core::log_escape(hello.scenario_hash()), scenario_hash));
  }
  if (std::find(domains.begin(), domains.end(), hello.domain()) == domains.end()) {
    return refuse(wire::ERROR_CODE_MODEL,
                  fmt::format("unknown domain '{}': the scenario's domains are '{}'; fix: start "
                              "the daemon with one of these names",
                              domain, fmt::join(domains, "', '")));
  }
  return std::nullopt;
}

wire::Envelope make_error(wire::ErrorCode code, std::string message, std::string domain) {
  wire::Envelope e;
  auto* error = e.mutable_error();
  error->set_code(code);
  error->set_message(std::move(message));
  error->set_domain(std::move(domain));
  return e;
}

wire::Envelope make_bye(std::string reason) {
  wire::Envelope e;
  e.mutable_bye()->set_reason(std::move(reason));
  return e;
}

}  // namespace crashlink::transport
