#pragma once
// Typed errors (docs/design.md §7 rule 6). Always-on checks throw one of these; the message carries
// the offending values and the fix. Internal invariants use CRASHLINK_ASSERT (debug only).
#include <fmt/format.h>

#include <cassert>
#include <stdexcept>
#include <string>

namespace crashlink {

/// Base of every error crashlink throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input: a scenario file, a command-line option. Message: "file:line: key: what; fix".
class InputError : public Error {
 public:
  InputError(const std::string& file, int line, const std::string& key, const std::string& what);
  explicit InputError(const std::string& what) : Error(what) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string key_;
};

/// A numerical blow-up detected by the guard: NaN, negative Jacobian, energy balance, instability.
/// Message says what happened, where (element / node / domain) and when (cycle, time).
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// A file that cannot be written or read back: disk full, read-only file system, no permission,
/// a folder where a file is meant (run::kExitIo). Message: the file, the system's reason, the fix.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A model that cannot be run as built (inconsistent sizes, a node in no element, ...).
class ModelError : public Error {
 public:
  using Error::Error;
};

}  // namespace crashlink

/// Debug-only check of an internal invariant.
#define CRASHLINK_ASSERT(cond) assert(cond)
