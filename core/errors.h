#pragma once
// Typed errors (docs/design.md §7 rule 6). Always-on checks throw one of these; the message carries
// the offending values and the fix. Internal invariants use CRASHLINK_ASSERT (debug only).
#include <fmt/format.h>

#include <cassert>
#include <stdexcept>
#include <string>
#include <utility>

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
/// a folder where a file is meant (kExitIo). Message: the file, the system's reason, the fix.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A peer broke the protocol (docs/design.md §3): bytes that are not an Envelope, a message out of
/// its turn, a free state at another instant than the one imposed, a vector for an interface the
/// peer does not own. peer() names it (a domain, "coordinator", "lane"; empty when the catcher
/// knows who sent the message). The message gives the values and the rule broken.
class ProtocolError : public Error {
 public:
  explicit ProtocolError(const std::string& what) : Error(what) {}
  ProtocolError(std::string peer, const std::string& what) : Error(what), peer_(std::move(peer)) {}
  const std::string& peer() const { return peer_; }

 private:
  std::string peer_;
};

/// A model that cannot be run as built (inconsistent sizes, a node in no element, ...).
class ModelError : public Error {
 public:
  using Error::Error;
};

}  // namespace crashlink

/// Debug-only check of an internal invariant.
#define CRASHLINK_ASSERT(cond) assert(cond)
