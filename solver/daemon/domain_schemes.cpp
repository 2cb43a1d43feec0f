#include "solver/daemon/domain_schemes.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <mutex>
#include <vector>

#include "solver/core/errors.h"
#include "solver/daemon/layer_domain_scheme.h"
#include "solver/daemon/paper_domain_scheme.h"

namespace crashlink::daemon {

namespace {

std::mutex& table_mutex() {
  static std::mutex m;
  return m;
}

std::deque<DomainSchemeEntry>& table() {
  static std::deque<DomainSchemeEntry> t{
      {"layer", partition::Scheme::Layer, make_layer_domain_scheme},
      {"paper", partition::Scheme::Paper, make_paper_domain_scheme},
  };
  return t;
}

}  // namespace

const std::deque<DomainSchemeEntry>& domain_schemes() {
  const std::scoped_lock lock(table_mutex());
  return table();
}

const DomainSchemeEntry& domain_scheme_named(std::string_view name) {
  const std::scoped_lock lock(table_mutex());
  std::vector<std::string> names;
  for (const auto& e : table()) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(
      fmt::format("no coupling scheme '{}'; the schemes are: {}", name, fmt::join(names, ", ")));
}

void register_domain_scheme(DomainSchemeEntry entry) {
  const std::scoped_lock lock(table_mutex());
  for (const auto& e : table())
    if (e.name == entry.name)
      throw InputError(fmt::format("coupling scheme '{}' is registered already", entry.name));
  table().push_back(std::move(entry));
}

}  // namespace crashlink::daemon
