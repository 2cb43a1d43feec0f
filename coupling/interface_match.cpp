#include "coupling/interface_match.h"

#include <algorithm>
#include <cmath>

namespace crashlink::coupling {

namespace {

struct Entry {
  std::int64_t id;
  int domain;
  std::int32_t local;
};

std::array<double, 3> position_of(const DomainInterface& d, std::int32_t i) {
  const auto j = static_cast<std::size_t>(i) * 3;
  return {d.positions_m[j], d.positions_m[j + 1], d.positions_m[j + 2]};
}

void check_domain(const DomainInterface& d) {
  const std::size_t n = d.node_ids.size();
  if (d.masses_kg.size() != n || d.positions_m.size() != 3 * n) {
    throw ModelError(fmt::format(
        "interface of domain '{}': {} node ids, {} masses and {} position values; expected one "
        "mass and 3 coordinates per node",
        d.domain, n, d.masses_kg.size(), d.positions_m.size()));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(d.masses_kg[i]) || d.masses_kg[i] < 0.0) {
      throw ModelError(fmt::format(
          "interface of domain '{}': node {} has mass {} kg; masses must be finite and >= 0",
          d.domain, d.node_ids[i], d.masses_kg[i]));
    }
    for (std::size_t c = 0; c < 3; ++c) {
      if (!std::isfinite(d.positions_m[3 * i + c])) {
        throw ModelError(fmt::format("interface of domain '{}': node {} has a non-finite position",
                                     d.domain, d.node_ids[i]));
      }
    }
  }
}

}  // namespace

std::vector<double> InterfaceTable::summed_masses(int k) const {
  std::vector<double> m;
  m.reserve(node_of[k].size());
  for (std::int32_t g : node_of[k]) m.push_back(nodes[static_cast<std::size_t>(g)].summed_mass_kg);
  return m;
}

std::vector<std::pair<int, int>> InterfaceTable::partner_pairs() const {
  std::vector<std::pair<int, int>> pairs;
  for (const InterfaceNode& node : nodes) {
    for (std::size_t a = 0; a < node.copies.size(); ++a) {
      for (std::size_t b = a + 1; b < node.copies.size(); ++b) {
        pairs.emplace_back(node.copies[a].domain, node.copies[b].domain);
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

InterfaceTable match_interfaces(std::span<const DomainInterface> domains,
                                double position_tolerance_m) {
  if (!(position_tolerance_m >= 0.0) || !std::isfinite(position_tolerance_m)) {
    throw ModelError(
        fmt::format("interface matching: position tolerance {} m; it must be finite and >= 0",
                    position_tolerance_m));
  }
  std::vector<Entry> entries;
  for (std::size_t k = 0; k < domains.size(); ++k) {
    check_domain(domains[k]);
    for (std::size_t i = 0; i < domains[k].node_ids.size(); ++i) {
      entries.push_back(
          {domains[k].node_ids[i], static_cast<int>(k), static_cast<std::int32_t>(i)});
    }
  }
  // By id, then domain: the copies of a node are consecutive, in increasing domain index.
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.id != b.id ? a.id < b.id : a.domain < b.domain;
  });

  InterfaceTable table;
  table.node_of.resize(domains.size());
  for (std::size_t k = 0; k < domains.size(); ++k) {
    table.node_of[k].assign(domains[k].node_ids.size(), -1);
  }
  for (std::size_t first = 0; first < entries.size();) {
    std::size_t last = first + 1;
    while (last < entries.size() && entries[last].id == entries[first].id) ++last;
    const std::int64_t id = entries[first].id;
    const DomainInterface& d0 = domains[static_cast<std::size_t>(entries[first].domain)];
    if (last - first == 1) {
      throw InterfaceError(
          id, {d0.domain},
          fmt::format("interface node {} is registered by domain '{}' only; every interface node "
                      "must be in at least two domains; fix: check the decomposition or the node "
                      "numbering of the partner domain",
                      id, d0.domain));
    }
    InterfaceNode node;
    node.id = id;
    node.position_m = position_of(d0, entries[first].local);
    for (std::size_t e = first; e < last; ++e) {
      const DomainInterface& d = domains[static_cast<std::size_t>(entries[e].domain)];
      if (e > first && entries[e].domain == entries[e - 1].domain) {
        throw ModelError(
            fmt::format("interface of domain '{}': node {} is registered twice", d.domain, id));
      }
      const auto p = position_of(d, entries[e].local);
      const double dist = std::hypot(p[0] - node.position_m[0], p[1] - node.position_m[1],
                                     p[2] - node.position_m[2]);
      if (!(dist <= position_tolerance_m)) {
        throw InterfaceError(
            id, {d0.domain, d.domain},
            fmt::format(
                "interface node {}: position ({}, {}, {}) m in domain '{}' and ({}, {}, {}) "
                "m in domain '{}' differ by {} m > tolerance {} m; fix: make the meshes "
                "conform at the interface or give the nodes distinct ids",
                id, node.position_m[0], node.position_m[1], node.position_m[2], d0.domain, p[0],
                p[1], p[2], d.domain, dist, position_tolerance_m));
      }
      const double m = d.masses_kg[static_cast<std::size_t>(entries[e].local)];
      node.summed_mass_kg += m;  // M = sum_k m^k, docs/design.md §2.2
      node.copies.push_back({entries[e].domain, entries[e].local, m});
    }
    if (!(node.summed_mass_kg > 0.0)) {
      throw InterfaceError(
          id, {d0.domain},
          fmt::format("interface node {}: summed mass {} kg over its {} copies; at least one "
                      "domain must give it a positive mass (contact copies have none)",
                      id, node.summed_mass_kg, node.copies.size()));
    }
    const auto g = static_cast<std::int32_t>(table.nodes.size());
    for (const NodeCopy& c : node.copies) {
      table.node_of[static_cast<std::size_t>(c.domain)][static_cast<std::size_t>(c.local)] = g;
    }
    table.nodes.push_back(std::move(node));
    first = last;
  }
  return table;
}

}  // namespace crashlink::coupling
