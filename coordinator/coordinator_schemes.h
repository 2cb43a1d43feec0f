#pragma once
// The coupling schemes a coordinator can run, by name (crashlink-coordinator --coupling NAME,
// Setup.scheme). Adding a scheme is one line in coordinator_schemes.cpp (and its daemon side in
// daemon/domain_schemes.cpp).
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "coordinator/coordinator_scheme.h"
#include "solver/model/model.h"

namespace crashlink::coordinator {

using MakeCoordinatorScheme = std::unique_ptr<CoordinatorScheme> (*)(
    const model::Model& model, const CoordinatorOptions& options);

/// The scheme's own rules on a run's configuration: InputError naming the option and the fix.
using ValidateCoupling = void (*)(const coupling::CouplingConfig& config);

struct CoordinatorSchemeEntry {
  std::string name;
  MakeCoordinatorScheme make = nullptr;
  ValidateCoupling validate = nullptr;  ///< nullptr: no rule of its own
};

/// Every scheme, the built-in ones first (a deque: registering keeps the references valid).
std::deque<CoordinatorSchemeEntry> coordinator_schemes();
/// Every scheme's name, the built-in ones first.
std::vector<std::string> coordinator_scheme_names();
/// The scheme named `name`; InputError listing the names otherwise.
const CoordinatorSchemeEntry& coordinator_scheme_named(std::string_view name);
/// Adds a scheme (a test's); InputError if the name is taken.
void register_coordinator_scheme(CoordinatorSchemeEntry entry);

/// Every rule on a run's configuration, in one place: the scheme exists, the values are in range,
/// and the scheme's own rules (`paper`: no checkpoints, no restart; `layer`: no --no-drift).
/// Called by `crashlink run` before anything starts and by the coordinator. Throws InputError.
void validate(const coupling::CouplingConfig& config);

}  // namespace crashlink::coordinator
