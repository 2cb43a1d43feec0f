#include "coordinator/coordinator_schemes.h"

#include <utility>

#include "coordinator/layer_coordinator_scheme.h"
#include "coordinator/paper_coordinator_scheme.h"
#include "coupling/named_table.h"

namespace crashlink::coordinator {

namespace {

coupling::NamedTable<CoordinatorSchemeEntry>& table() {
  static coupling::NamedTable<CoordinatorSchemeEntry> t({
      {"layer", make_layer_coordinator_scheme},
      {"paper", make_paper_coordinator_scheme},
  });
  return t;
}

}  // namespace

const std::deque<CoordinatorSchemeEntry>& coordinator_schemes() {
  return table().all();
}

const CoordinatorSchemeEntry& coordinator_scheme_named(std::string_view name) {
  return table().named(name);
}

void register_coordinator_scheme(CoordinatorSchemeEntry entry) {
  table().add(std::move(entry));
}

}  // namespace crashlink::coordinator
