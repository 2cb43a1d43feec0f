#pragma once
// A table of entries found by name, safe to extend while it is read from other threads (the
// in-process launcher runs a coordinator and daemons at once): the coupling schemes of each side
// (solver/daemon/domain_schemes.h, coordinator/coordinator_schemes.h). A deque keeps the
// references it hands out valid when an entry is added.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <deque>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace crashlink::coupling {

/// Entry has a `std::string name`.
template <class Entry>
class NamedTable {
 public:
  explicit NamedTable(std::deque<Entry> entries) : entries_(std::move(entries)) {}

  /// A copy: another thread may add an entry meanwhile.
  std::deque<Entry> all() const {
    const std::scoped_lock lock(mutex_);
    return entries_;
  }

  /// Every entry's name, in order (what a --coupling option accepts).
  std::vector<std::string> names() const {
    const std::scoped_lock lock(mutex_);
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }

  /// The entry named `name`; InputError listing the names otherwise.
  const Entry& named(std::string_view name) const {
    const std::scoped_lock lock(mutex_);
    std::vector<std::string> names;
    for (const auto& e : entries_) {
      if (e.name == name) return e;
      names.push_back(e.name);
    }
    throw InputError(
        fmt::format("no coupling scheme '{}'; the schemes are: {}", name, fmt::join(names, ", ")));
  }

  /// Adds an entry; InputError if its name is taken.
  void add(Entry entry) {
    const std::scoped_lock lock(mutex_);
    for (const auto& e : entries_)
      if (e.name == entry.name)
        throw InputError(fmt::format("coupling scheme '{}' is registered already", entry.name));
    entries_.push_back(std::move(entry));
  }

 private:
  mutable std::mutex mutex_;
  std::deque<Entry> entries_;
};

}  // namespace crashlink::coupling
