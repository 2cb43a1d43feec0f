#pragma once
// Matching of interface nodes across domains (docs/design.md §2.2). Each domain registers its
// interface nodes by global node id with its own lumped mass m^k and position; the coordinator
// pairs the copies of a node by id, sums the mass, M = sum_k m^k ([2.2]; the free accelerations
// of [5] are over M, the link correction [8] adds them), and sends M back in Setup.
// Always-on checks (docs/design.md §7 rule 6): a node registered by one domain only, copies whose
// positions differ by more than the tolerance, duplicate ids, bad masses or sizes.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace crashlink::coupling {

/// One domain's Register (proto Register), as plain arrays.
struct DomainInterface {
  std::string domain;                  // name, for messages
  std::vector<std::int64_t> node_ids;  // global ids, this domain's order (n)
  std::vector<double> masses_kg;       // own mass m^k per node (n); 0 for a contact copy
  std::vector<double> positions_m;     // xyz interleaved (3 n)
};

/// One domain's copy of an interface node.
struct NodeCopy {
  int domain = -1;          // index into the match_interfaces input
  std::int32_t local = -1;  // index in that domain's node_ids
  double mass_kg = 0.0;
};

struct InterfaceNode {
  std::int64_t id = 0;
  double summed_mass_kg = 0.0;         // M = sum_k m^k ([2.2])
  std::array<double, 3> position_m{};  // position of the copy in the lowest-index domain
  std::vector<NodeCopy> copies;        // >= 2, in increasing domain index
};

struct InterfaceTable {
  std::vector<InterfaceNode> nodes;                // sorted by id
  std::vector<std::vector<std::int32_t>> node_of;  // [domain][local] -> index into nodes

  /// M per node in domain k's Register order (Setup.summed_masses_kg).
  std::vector<double> summed_masses(int k) const;
  /// Undirected pairs (k, l), k < l, of domains sharing at least one node, sorted: the partner
  /// graph of the schedule (schedule.h).
  std::vector<std::pair<int, int>> partner_pairs() const;
};

/// An interface node that cannot be linked: registered by one domain only, or with copies at
/// different positions. Names the node and the domains involved.
class InterfaceError : public ModelError {
 public:
  InterfaceError(std::int64_t node_id, std::vector<std::string> domains, const std::string& what)
      : ModelError(what), node_id_(node_id), domains_(std::move(domains)) {}
  std::int64_t node_id() const { return node_id_; }
  const std::vector<std::string>& domains() const { return domains_; }

 private:
  std::int64_t node_id_;
  std::vector<std::string> domains_;
};

/// Matches the nodes of all domains by id. position_tolerance_m >= 0: largest distance between
/// two copies of a node, m. Throws InterfaceError for the lowest offending node id, ModelError for
/// inconsistent input (sizes, duplicate id in a domain, negative or non-finite mass or position,
/// a node whose summed mass is not positive).
InterfaceTable match_interfaces(std::span<const DomainInterface> domains,
                                double position_tolerance_m);

}  // namespace crashlink::coupling
