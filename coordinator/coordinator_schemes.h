#pragma once
// The coupling schemes a coordinator can run, by name (crashlink-coordinator --coupling NAME,
// Setup.scheme). Adding a scheme is one line in coordinator_schemes.cpp (and its daemon side in
// daemon/domain_schemes.cpp).
#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "coordinator/coordinator_scheme.h"
#include "solver/model/model.h"

namespace crashlink::coordinator {

using MakeCoordinatorScheme = std::unique_ptr<CoordinatorScheme> (*)(
    const model::Model& model, const CoordinatorOptions& options, const std::string& hash);

struct CoordinatorSchemeEntry {
  std::string name;
  MakeCoordinatorScheme make = nullptr;
};

/// Every scheme, the built-in ones first (a deque: registering keeps the references valid).
const std::deque<CoordinatorSchemeEntry>& coordinator_schemes();
/// The scheme named `name`; InputError listing the names otherwise.
const CoordinatorSchemeEntry& coordinator_scheme_named(std::string_view name);
/// Adds a scheme (a test's); InputError if the name is taken.
void register_coordinator_scheme(CoordinatorSchemeEntry entry);

}  // namespace crashlink::coordinator
