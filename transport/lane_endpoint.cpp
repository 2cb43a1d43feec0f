#include "transport/lane_endpoint.h"

#include <fmt/format.h>

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
      const std::string path = fmt::format("{}.{}.lane", c.address, domain);
      if (path.size() <= kMaxIpcPath) return "ipc://" + path;
      return local_endpoint(Scheme::ipc, fmt::format("lane-{}", domain));
    }
    case Scheme::tcp: {
      const auto colon = c.address.rfind(':');
      return fmt::format("tcp://{}:*", c.address.substr(0, colon));
    }
  }
  return {};
}

}  // namespace crashlink::transport
