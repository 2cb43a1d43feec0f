#pragma once
// Internal to crashlink::partition: the analysis of the global model shared by both schemes and
// the placement (which element and node goes where) from which the sub-models are built.
//
// Element numbering: "flat" index e = offset[p] + k for element k of global part p.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::partition::detail {

/// Node roles in one domain.
enum NodeRole : std::uint8_t { kAbsent = 0, kOwned = 1, kGhost = 2, kCopy = 3 };

struct Analysis {
  const model::Model* global = nullptr;
  std::vector<std::string> domain_name;  ///< [domains]
  std::vector<int> part_domain;          ///< [parts] original domain of each part
  std::vector<std::size_t> offset;       ///< [parts + 1] first flat element of each part
  std::vector<int> elem_part;            ///< [elements] global part of flat element e
  std::vector<std::int32_t> elem_local;  ///< [elements] index inside that part
  std::vector<int> orig_domain;          ///< [elements] domain of the element's part
  std::vector<std::size_t> node_start;   ///< [n + 1] CSR: elements of node n at
  std::vector<std::int32_t> node_elems;  ///< node_elems[node_start[n] .. node_start[n+1])
  std::vector<double> part_dt_s;         ///< [parts] initial stable step x dt_scale; +inf rigid
  std::vector<double> orig_dt_s;         ///< [domains] min over the domain's parts
  std::vector<double> mass_kg;           ///< [n] natural lumped mass over the whole model
  std::vector<int> body_of_part;         ///< [parts] rigid body index or -1
  /// The whole model's energy scale [J] (integration::model_energy_scale_J), every domain's
  /// guard floor (Controls::model_energy_scale_J).
  double energy_scale_J = 0.0;

  std::size_t domain_count() const { return domain_name.size(); }
  std::size_t element_count() const { return elem_part.size(); }
  std::size_t node_count() const { return node_start.size() - 1; }
  /// Total order "a is finer than b": smaller step, ties broken by the earlier domain.
  bool finer(int a, int b) const {
    const double da = orig_dt_s[static_cast<std::size_t>(a)];
    const double db = orig_dt_s[static_cast<std::size_t>(b)];
    return da < db || (da == db && a < b);
  }
  std::int64_t element_id(std::size_t e) const;
  std::int64_t node_id(std::size_t n) const { return global->nodes.id[n]; }
  /// Node indices of flat element e (k = 8 or 4 entries).
  const std::int32_t* element_nodes(std::size_t e, int& k) const;
};

/// Checks global.domains (every part in exactly one domain, no empty domain, a rigid body in one
/// domain), runs integration::Solver(global).initialize() once for the per-part steps and the
/// lumped masses, and builds the adjacency. No domains: one domain "model" with every part.
Analysis analyse(const model::Model& global);

/// The sides of contact c on the ORIGINAL assignment: the master parts' domain A (all master
/// parts must be in one domain), the other domains the slave nodes lie in (a greedy cover: A
/// first, then the domain holding most of the remaining slave nodes, ...), and the contact's
/// surface elements: every element of the master parts and every element of a covering domain
/// that contains a slave node.
struct ContactSides {
  int master_domain = -1;
  std::vector<int> slave_domains;     ///< covering domains other than A (ascending)
  std::vector<std::int32_t> surface;  ///< flat elements
  std::vector<int> slave_home;        ///< [slave nodes] covering domain of each slave node
};
ContactSides contact_sides(const Analysis& a, std::size_t c);

/// Where everything goes.
struct Placement {
  std::vector<int> elem_domain;                 ///< [elements] final domain
  std::vector<std::vector<std::uint8_t>> role;  ///< [domains][n] NodeRole
  std::vector<int> primary;                     ///< [n] domain carrying loads and node probes
  std::vector<std::uint8_t> summed;             ///< [n] 1: integrate with mass_kg[n] (shared)
  std::vector<int> contact_domain;              ///< [contacts]
  /// [elements] or empty: interface damping ratio of each element (layer,
  /// model::InterfaceDamping; 0: not near an interface); the sub-model takes max(own, this).
  std::vector<double> elem_damping_ratio;
};

/// [elements] model::InterfaceDamping::ratio on every deformable element within `layers` element
/// layers of a node flagged in `seed` ([n], the layer's far nodes J), 0 elsewhere; empty when the
/// ratio is 0. Layer 1 = the elements touching a seed node, layer k+1 = those touching a node of
/// layer k (both sides of J, whatever their domain).
std::vector<double> interface_damping(const Analysis& a, const std::vector<std::uint8_t>& seed);

/// Builds domain d's sub-model from the placement and validates it (model::validate).
DomainModel build_domain(const Analysis& a, const Placement& p, int d);

/// Builds every domain's sub-model (build_domain) into out.domains and its initial step into
/// out.domain_dt_s: the last stage of both schemes.
void build_domains(const Analysis& a, const Placement& p, std::size_t domain_count,
                   Decomposition& out);

/// Initial stable step x dt_scale of a (sub-)model's deformable parts (+inf if none): the
/// minimum over parts of integration::Solver's per-part step at t = 0.
double initial_step_s(const model::Model& m);

Decomposition decompose_layer(const Analysis& a, int overlap_layers);
Decomposition decompose_paper(const Analysis& a);

}  // namespace crashlink::partition::detail
