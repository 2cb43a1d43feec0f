#include "solver/coordination/coordinator_schemes.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <mutex>
#include <vector>

#include "solver/coordination/layer_coordinator_scheme.h"
#include "solver/coordination/paper_coordinator_scheme.h"
#include "solver/core/errors.h"

namespace crashlink::coordination {

namespace {

std::mutex& table_mutex() {
  static std::mutex m;
  return m;
}

std::deque<CoordinatorSchemeEntry>& table() {
  static std::deque<CoordinatorSchemeEntry> t{
      {"layer", make_layer_coordinator_scheme},
      {"paper", make_paper_coordinator_scheme},
  };
  return t;
}

}  // namespace

const std::deque<CoordinatorSchemeEntry>& coordinator_schemes() {
  const std::scoped_lock lock(table_mutex());
  return table();
}

const CoordinatorSchemeEntry& coordinator_scheme_named(std::string_view name) {
  const std::scoped_lock lock(table_mutex());
  std::vector<std::string> names;
  for (const auto& e : table()) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(
      fmt::format("no coupling scheme '{}'; the schemes are: {}", name, fmt::join(names, ", ")));
}

void register_coordinator_scheme(CoordinatorSchemeEntry entry) {
  const std::scoped_lock lock(table_mutex());
  for (const auto& e : table())
    if (e.name == entry.name)
      throw InputError(fmt::format("coupling scheme '{}' is registered already", entry.name));
  table().push_back(std::move(entry));
}

}  // namespace crashlink::coordination
