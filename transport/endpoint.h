#pragma once
// ZeroMQ endpoint strings (docs/design.md §3): the three transports crashlink runs on.
//   tcp://host:port     host a name, an IPv4 address, [IPv6] or * (bind: every interface);
//                       port 1-65535, or * / 0 to bind an ephemeral port (read back with
//                       Router::endpoint(); tests always bind tcp://127.0.0.1:*, no fixed ports)
//   ipc://path          a Unix socket file; the path is at most 107 bytes (sun_path)
//   inproc://name       threads of one process; both sides use the process-wide context
//                       (detail/zmq.h), so any Router and Dealer of the process can pair
// parse_endpoint validates a string and throws TransportError with the reason and the fix.
#include <cstddef>
#include <string>
#include <string_view>

namespace crashlink::transport {

enum class Scheme { tcp, ipc, inproc };

/// Whether an endpoint is bound (coordinator) or connected (daemon): `*` ports only bind.
enum class Use { bind, connect };

struct Endpoint {
  Scheme scheme = Scheme::tcp;
  std::string address;  // tcp: "host:port"; ipc: the path; inproc: the name
  std::string text;     // the whole endpoint string, as ZeroMQ takes it

  /// tcp with port * or 0: the real port is known only after the bind.
  bool ephemeral() const;
};

/// Longest ipc:// path: sizeof(sockaddr_un::sun_path) - 1 on Linux.
inline constexpr std::size_t kMaxIpcPath = 107;

/// Parses and validates `text` for `use`; throws TransportError naming the endpoint, what is wrong
/// and the expected form.
Endpoint parse_endpoint(std::string_view text, Use use);

std::string_view scheme_name(Scheme scheme);

/// A fresh local endpoint to bind, unique in this process and (for ipc) on this machine:
/// tcp -> "tcp://127.0.0.1:*" (ephemeral port); ipc -> "ipc://<temp dir>/crashlink-<pid>-<n>-<tag>"
/// (temp dir = $TMPDIR or /tmp; the file is removed when the Router closes); inproc ->
/// "inproc://crashlink-<n>-<tag>". For tests, benchmarks and `crashlink run` on one machine.
std::string local_endpoint(Scheme scheme, std::string_view tag = "link");

}  // namespace crashlink::transport
