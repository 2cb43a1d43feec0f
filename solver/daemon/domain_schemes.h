#pragma once
// The coupling schemes a daemon can run, by name (crashlink-solver --coupling NAME, Setup.scheme):
// how each cuts the scenario and how it builds its coupling::DomainScheme. Adding a scheme is one
// line in domain_schemes.cpp (and its coordinator side in coordination/coordinator_schemes.cpp).
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/domain_scheme.h"
#include "solver/partition/decomposition.h"

namespace crashlink::daemon {

using MakeDomainScheme = std::unique_ptr<coupling::DomainScheme> (*)(
    const partition::Decomposition& dec, const model::Model& model,
    const coupling::DomainSchemeOptions& options);

struct DomainSchemeEntry {
  std::string name;
  partition::Scheme cut = partition::Scheme::Layer;  ///< how the scenario is cut into domains
  MakeDomainScheme make = nullptr;
  /// Layer cut: the coarse element layers moved beyond the first (`lts`, partition::decompose).
  int overlap_layers = 0;
};

/// Every scheme, the built-in ones first (a deque: registering keeps the references valid).
std::deque<DomainSchemeEntry> domain_schemes();
/// Every scheme's name, the built-in ones first.
std::vector<std::string> domain_scheme_names();
/// The scheme named `name`; InputError listing the names otherwise.
const DomainSchemeEntry& domain_scheme_named(std::string_view name);
/// Adds a scheme (a test's); InputError if the name is taken.
void register_domain_scheme(DomainSchemeEntry entry);

}  // namespace crashlink::daemon
