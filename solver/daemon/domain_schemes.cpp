#include "solver/daemon/domain_schemes.h"

#include <utility>

#include "coupling/coupling_config.h"
#include "coupling/named_table.h"
#include "solver/daemon/layer_domain_scheme.h"
#include "solver/daemon/paper_domain_scheme.h"

namespace crashlink::daemon {

namespace {

coupling::NamedTable<DomainSchemeEntry>& table() {
  static coupling::NamedTable<DomainSchemeEntry> t({
      {"layer", partition::Scheme::Layer, make_layer_domain_scheme},
      {"paper", partition::Scheme::Paper, make_paper_domain_scheme},
      {"lts", partition::Scheme::Layer, make_lts_domain_scheme, coupling::kLtsOverlapLayers},
  });
  return t;
}

}  // namespace

std::deque<DomainSchemeEntry> domain_schemes() {
  return table().all();
}

std::vector<std::string> domain_scheme_names() {
  return table().names();
}

const DomainSchemeEntry& domain_scheme_named(std::string_view name) {
  return table().named(name);
}

void register_domain_scheme(DomainSchemeEntry entry) {
  table().add(std::move(entry));
}

}  // namespace crashlink::daemon
