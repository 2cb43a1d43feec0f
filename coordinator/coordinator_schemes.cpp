#include "coordinator/coordinator_schemes.h"

#include <fmt/format.h>

#include <utility>

#include "coordinator/layer_coordinator_scheme.h"
#include "coordinator/paper_coordinator_scheme.h"
#include "core/errors.h"
#include "coupling/named_table.h"

namespace crashlink::coordinator {

namespace {

coupling::NamedTable<CoordinatorSchemeEntry>& table() {
  static coupling::NamedTable<CoordinatorSchemeEntry> t({
      {"layer", make_layer_coordinator_scheme, validate_layer_config},
      {"paper", make_paper_coordinator_scheme, validate_paper_config},
      {"lts", make_lts_coordinator_scheme, validate_lts_config},
  });
  return t;
}

}  // namespace

std::deque<CoordinatorSchemeEntry> coordinator_schemes() {
  return table().all();
}

std::vector<std::string> coordinator_scheme_names() {
  return table().names();
}

const CoordinatorSchemeEntry& coordinator_scheme_named(std::string_view name) {
  return table().named(name);
}

void register_coordinator_scheme(CoordinatorSchemeEntry entry) {
  table().add(std::move(entry));
}

void validate(const coupling::CouplingConfig& c) {
  const auto& entry = coordinator_scheme_named(c.scheme);
  if (!(c.checkpoint_interval_s >= 0.0))
    throw InputError(
        fmt::format("--checkpoint-interval {}: must be >= 0 s (0: none)", c.checkpoint_interval_s));
  if (c.ticks_per_second < 1)
    throw InputError(fmt::format("{} ticks per second: must be >= 1", c.ticks_per_second));
  if (!(c.guard_rise > 0.0))
    throw InputError(fmt::format("energy guard rise {}: must be > 0", c.guard_rise));
  if (entry.validate != nullptr) entry.validate(c);
}

}  // namespace crashlink::coordinator
