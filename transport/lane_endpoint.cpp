#include "transport/lane_endpoint.h"

#include <fmt/format.h>

#include <filesystem>
#include <functional>

#include "transport/curve_policy.h"
#include "transport/endpoint.h"

namespace crashlink::transport {

std::string lane_endpoint_for(std::string_view coordinator_endpoint, std::string_view domain,
                              const CurveOptions& curve) {
  const Endpoint c = parse_endpoint(coordinator_endpoint, Use::connect);
  if (!is_local_endpoint(c) || curve_on(c, curve)) return {};
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
