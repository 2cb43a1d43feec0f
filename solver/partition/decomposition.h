#pragma once
// Cutting a global model into per-domain sub-models for the two coupling schemes of docs/design.md
// §2 (Scheme: layer; paper, after Bourel 2005). Pure functions over model::Model; no networking, no
// solution state. Rules and figure: docs/decomposition.md. Array shapes: on each field (n_local =
// local node count of a domain, n_J = node count of an interface).
#include <cstdint>
#include <string>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::partition {

/// How decompose() cuts:
///   Layer (docs/design.md §2.7, the default): at every interface the domain with the smaller
///     stable step (fine, F) takes the coarse side's (C) first element layer; F owns its elements,
///     the moved layer and all their nodes except the layer's far nodes J; J are read-only ghosts
///     in F, owned by C with their natural summed lumped mass (no added mass). Every contact ends
///     up inside one domain.
///   Paper (docs/design.md §2.2 and §2.5, Bourel 2005 §2.3-§3 and [3]-[11]): no element moves; a
///     link node is present in every domain whose elements use it, each with its partial lumped
///     mass (the coordinator sums them, [5]); for a contact across domains, the master's domain A
///     gets copies of the other domain's slave nodes (no elements, no own mass) and computes the
///     contact on them (§3.1 of Bourel 2005).
enum class Scheme : std::uint8_t { Layer, Paper };

/// One domain's sub-model. Node and element user ids are the global ones; indices are local.
/// Each local part keeps the global element order, except that the elements on a ghost node come
/// last (Solver::interior_elements).
struct DomainModel {
  std::string name;
  model::Model model;
  std::vector<std::int32_t> global_node;  ///< [n_local] local -> global node index (ascending)
  /// [n_local] 1: read-only ghost whose motion the coupling prescribes (layer: the far nodes J of
  /// a layer this domain took; never in paper).
  std::vector<std::uint8_t> ghost;
  /// [n_local] 1: a copy of another domain's slave node (paper, §3.1 of Bourel 2005): no element,
  /// no own mass, tied to its original by the link [8]. Never in layer.
  std::vector<std::uint8_t> copy;
  /// [n_local] > 0: integrate this node with this summed mass [kg] instead of the local lumped mass
  /// (layer: J on its owner; paper: every shared or copied node, M = sum_k m^k of §2.2). 0: local.
  std::vector<double> interface_mass_kg;
  std::vector<int> part_global;  ///< [local parts] local part -> global part index
  /// [local parts][local elements] local element -> element index inside the global part.
  std::vector<std::vector<std::int32_t>> part_elements;

  bool empty() const { return model.parts.empty(); }
};

/// A coupling interface between two domains (indices into Decomposition::domains).
struct Interface {
  int fine = -1;    ///< the domain with the smaller step (ties: the earlier domain)
  int coarse = -1;  ///< the other one
  /// Drift-correction reference [11] / owner of the interface nodes: layer: coarse (owns J);
  /// paper: the larger-step domain for a link, the domain owning the originals for copies.
  int reference = -1;
  /// layer: the far nodes J of the moved layer (owned by coarse, ghosts in fine);
  /// paper: the shared nodes (link) or the copied slave nodes (contact). [n_J] ascending global
  /// indices.
  std::vector<std::int32_t> j_nodes_global;
  /// [n_J] natural lumped mass of each node summed over every element of the global model [kg].
  std::vector<double> j_mass_kg;
  /// layer: global user ids of the elements moved from coarse into fine (ascending); paper: none.
  std::vector<std::int64_t> moved_elements;
  /// Why the interface exists: "link" or "contact:<name>"; several reasons joined by '+'
  /// (e.g. "link+contact:head_on_plate").
  std::string kind;
};

struct Decomposition {
  Scheme scheme = Scheme::Layer;
  std::vector<DomainModel> domains;  ///< Model::domains order (one "model" domain if none)
  std::vector<Interface> interfaces;
  /// [domains] initial stable step x dt_scale of each domain as cut [s]; +inf: no deformable
  /// element (rigid bodies only, or emptied by the move).
  std::vector<double> domain_dt_s;
  /// Layer: the coarse element layers moved into the finer domain beyond the first (decompose).
  int overlap_layers = 0;
};

/// Cuts `global` along global.domains (checked: every part in exactly one domain, no empty
/// domain, a rigid body inside one domain). Throws ModelError with the fix when the model cannot
/// be cut by the scheme's rules (e.g. a contact spanning three domains). Each sub-model passes
/// model::validate.
/// Layer: `overlap_layers` >= 0 further coarse element layers go into the finer domain after the
/// first (the `lts` scheme's overlap, docs/multirate.md "lts"): the link claim repeated on the new
/// assignment. 0 is the `layer` cut. Paper: must be 0 (ModelError otherwise).
Decomposition decompose(const model::Model& global, Scheme scheme, int overlap_layers = 0);

/// "layer" / "paper".
const char* scheme_name(Scheme s);

}  // namespace crashlink::partition
