#pragma once
// When CURVE is on, and the keys it then needs (docs/processes.md, "Security (CURVE)"):
//   - tcp to a loopback host (127.0.0.0/8, ::1, localhost), ipc:// and inproc:// are local: no
//     CURVE unless CurveOptions::force (inproc never: nothing leaves the process);
//   - any other tcp endpoint (a host name, an address, * or 0.0.0.0 to bind every interface)
//     always uses CURVE, and a missing key file is a CurveConfigError naming the endpoint, what
//     is missing and the fix.
#include <optional>
#include <string>
#include <vector>

#include "transport/curve_options.h"
#include "transport/endpoint.h"

namespace crashlink::transport {

/// Whether `endpoint` stays on this machine: loopback tcp, ipc, inproc.
bool is_local_endpoint(const Endpoint& endpoint);

/// Whether a socket on `endpoint` uses CURVE with `options`.
bool curve_on(const Endpoint& endpoint, const CurveOptions& options);

/// The coordinator's keys, read from their files.
struct CurveServerKeys {
  std::string secret_key;
  std::string public_key;  ///< of secret_key (for messages: what daemons must be given)
  std::vector<std::string> authorized;
  std::string authorized_file;
  bool authorize_later = false;  ///< CurveOptions::authorize_later
};

/// A daemon's keys, read from their files.
struct CurveClientKeys {
  std::string secret_key;
  std::string public_key;  ///< of secret_key
  std::string server_key;
};

/// nullopt when CURVE is off for `endpoint`; otherwise the keys. Throws CurveConfigError (a file
/// not given) or CurveKeyFileError (a file that is not usable).
std::optional<CurveServerKeys> curve_server_keys(const Endpoint& endpoint,
                                                 const CurveOptions& options);
std::optional<CurveClientKeys> curve_client_keys(const Endpoint& endpoint,
                                                 const CurveOptions& options);

}  // namespace crashlink::transport
