#include "transport/lane_endpoint.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "transport/curve_policy.h"
#include "transport/endpoint.h"

namespace crashlink::transport {

std::string local_address_towards(const std::string& host, const std::string& port) {
  // A UDP "connect" sends nothing: it only makes the kernel choose the route and so the local
  // address a peer on that network reaches us at.
  const std::string h =
      host.size() > 2 && host.front() == '[' ? host.substr(1, host.size() - 2) : host;
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* res = nullptr;
  if (::getaddrinfo(h.c_str(), port.c_str(), &hints, &res) != 0 || res == nullptr) return {};
  std::string out;
  for (addrinfo* a = res; a != nullptr && out.empty(); a = a->ai_next) {
    const int fd = ::socket(a->ai_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0) continue;
    sockaddr_storage local{};
    socklen_t len = sizeof local;
    if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len) == 0) {
      char text[INET6_ADDRSTRLEN] = {};
      if (local.ss_family == AF_INET) {
        const auto* in = reinterpret_cast<const sockaddr_in*>(&local);
        if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text) != nullptr) out = text;
      } else if (local.ss_family == AF_INET6) {
        const auto* in6 = reinterpret_cast<const sockaddr_in6*>(&local);
        if (::inet_ntop(AF_INET6, &in6->sin6_addr, text, sizeof text) != nullptr)
          out = fmt::format("[{}]", text);
      }
    }
    ::close(fd);
  }
  ::freeaddrinfo(res);
  return out;
}

std::string lane_endpoint_for(std::string_view coordinator_endpoint, std::string_view domain,
                              const CurveOptions& curve) {
  const Endpoint c = parse_endpoint(coordinator_endpoint, Use::connect);
  if (!is_local_endpoint(c)) {
    // Across hosts: on the address that reaches the coordinator, an ephemeral port; CURVE is
    // always on there (curve_policy.h), with this daemon's own keys.
    if (c.scheme != Scheme::tcp) return {};
    const auto colon = c.address.rfind(':');
    const std::string local =
        local_address_towards(c.address.substr(0, colon), c.address.substr(colon + 1));
    return local.empty() ? std::string() : fmt::format("tcp://{}:*", local);
  }
  if (curve_on(c, curve)) return {};  // CURVE forced on a local session: through the coordinator
  switch (c.scheme) {
    case Scheme::inproc:
      return fmt::format("inproc://{}.lane.{}", c.address, domain);
    case Scheme::ipc: {
      // One machine: shared memory (shm_lane.h), in /dev/shm (memory, never written back to a
      // disk) under a name unique to the session's socket, else beside the socket file.
      std::error_code ec;
      if (std::filesystem::is_directory("/dev/shm", ec)) {
        return fmt::format("shm:///dev/shm/crashlink-{:016x}.{}",
                           std::hash<std::string>{}(c.address), domain);
      }
      return fmt::format("shm://{}.{}", c.address, domain);
    }
    case Scheme::tcp: {
      const auto colon = c.address.rfind(':');
      return fmt::format("tcp://{}:*", c.address.substr(0, colon));
    }
  }
  return {};
}

}  // namespace crashlink::transport
