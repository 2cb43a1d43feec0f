#pragma once
// A checkpoint file (docs/design.md §2.6 "Checkpoints", issue #6 item 5): named binary records, so
// that a restarted run continues from exactly the bits an uninterrupted run had.
//
// File layout (little-endian, the machine's own double format: a checkpoint is read back by the
// same build on the same kind of machine; a foreign file is refused by the magic and the check):
//   magic "CRASHLINK-STATE\n" (16 bytes), format version u32,
//   records: name length u32, name bytes, type u8 (Type), count u64, count * sizeof(type) bytes,
//   trailer: the FNV-1a 64 hash of every byte before it (u64).
// StateWriter::save writes PATH.tmp, fsyncs it and renames it to PATH: a reader sees a complete
// file or none. StateReader checks the magic, the version and the hash, and every get() checks
// the record's name, type and (get_exact) count, throwing CheckpointError with the fix.
#include <cstdint>
#include <cstring>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/errors.h"

namespace crashlink {

/// A checkpoint that cannot be written, read or used (missing, damaged, another model or run).
class CheckpointError : public InputError {
 public:
  using InputError::InputError;
};

namespace core {

/// FNV-1a 64 of n bytes (Fowler, Noll, Vo): h = (h xor byte) * 1099511628211 for each byte, from
/// the offset basis 1469598103934665603, or from `h` to continue a hash over several buffers.
std::uint64_t fnv1a(const std::uint8_t* p, std::size_t n, std::uint64_t h = 1469598103934665603ull);

class StateWriter {
 public:
  void put(std::string_view name, std::span<const double> v);
  void put(std::string_view name, std::span<const std::int64_t> v);
  void put(std::string_view name, std::span<const std::int32_t> v);
  void put(std::string_view name, std::span<const std::uint8_t> v);
  void put(std::string_view name, std::span<const std::int8_t> v);
  void put_double(std::string_view name, double x) { put(name, std::span<const double>(&x, 1)); }
  void put_int(std::string_view name, std::int64_t x) {
    put(name, std::span<const std::int64_t>(&x, 1));
  }
  void put_bool(std::string_view name, bool b) { put_int(name, b ? 1 : 0); }
  void put_string(std::string_view name, std::string_view s);
  /// Raw bytes of a trivially copyable value (Vec3, Mat3, small structs of doubles).
  template <class T>
  void put_pod(std::string_view name, const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(name, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(&x), sizeof x));
  }

  /// Writes PATH atomically (PATH.tmp, fsync, rename, fsync of the folder). Throws
  /// CheckpointError naming the path and the system's reason.
  void save(const std::string& path) const;
  std::size_t bytes() const { return body_.size(); }

 private:
  void record(std::string_view name, std::uint8_t type, std::size_t count, const void* data,
              std::size_t bytes);
  std::vector<std::uint8_t> body_;
};

class StateReader {
 public:
  /// Reads and checks the whole file; throws CheckpointError (absent, truncated, damaged, other
  /// format version).
  explicit StateReader(std::string path);

  bool has(std::string_view name) const { return index_.count(std::string(name)) != 0; }
  /// Any length (the record's own).
  void get(std::string_view name, std::vector<double>& v) const;
  void get(std::string_view name, std::vector<std::int64_t>& v) const;
  void get(std::string_view name, std::vector<std::int32_t>& v) const;
  void get(std::string_view name, std::vector<std::uint8_t>& v) const;
  void get(std::string_view name, std::vector<std::int8_t>& v) const;
  /// The record must have exactly v.size() values (arrays sized by the model): a checkpoint of
  /// another model is refused here, naming the record and both sizes.
  template <class T>
  void get_exact(std::string_view name, std::vector<T>& v) const {
    const std::size_t want = v.size();
    get(name, v);
    if (v.size() != want) size_mismatch(name, v.size(), want);
  }
  double get_double(std::string_view name) const;
  std::int64_t get_int(std::string_view name) const;
  bool get_bool(std::string_view name) const { return get_int(name) != 0; }
  std::string get_string(std::string_view name) const;
  template <class T>
  void get_pod(std::string_view name, T& x) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::uint8_t> b;
    get(name, b);
    if (b.size() != sizeof x) size_mismatch(name, b.size(), sizeof x);
    std::memcpy(&x, b.data(), sizeof x);
  }
  const std::string& path() const { return path_; }

 private:
  struct Entry {
    std::uint8_t type = 0;
    std::size_t count = 0;
    std::size_t offset = 0;  // of the data in bytes_
  };
  const Entry& find(std::string_view name, std::uint8_t type) const;
  [[noreturn]] void size_mismatch(std::string_view name, std::size_t got, std::size_t want) const;
  template <class T>
  void get_any(std::string_view name, std::uint8_t type, std::vector<T>& v) const;

  std::string path_;
  std::vector<std::uint8_t> bytes_;
  std::map<std::string, Entry> index_;
};

/// Visitors for a state saved and restored by ONE list of fields (Solver::visit_state): the list
/// calls v.vec / v.sized / v.num / v.integer / v.flag / v.pod on each member; StateSave writes it,
/// StateLoad reads it back into the same member (sized: the record must have the member's current
/// length, i.e. the model's). `loading` tells the list which way it goes where it must differ.
struct StateSave {
  static constexpr bool loading = false;
  StateWriter& w;
  template <class T>
  void vec(std::string_view n, const std::vector<T>& v) {
    w.put(n, std::span<const T>(v));
  }
  template <class T>
  void sized(std::string_view n, const std::vector<T>& v) {
    vec(n, v);
  }
  void num(std::string_view n, double x) { w.put_double(n, x); }
  template <class T>
  void integer(std::string_view n, T x) {
    w.put_int(n, static_cast<std::int64_t>(x));
  }
  void flag(std::string_view n, bool b) { w.put_bool(n, b); }
  template <class T>
  void pod(std::string_view n, const T& x) {
    w.put_pod(n, x);
  }
};

struct StateLoad {
  static constexpr bool loading = true;
  const StateReader& r;
  template <class T>
  void vec(std::string_view n, std::vector<T>& v) {
    r.get(n, v);
  }
  template <class T>
  void sized(std::string_view n, std::vector<T>& v) {
    r.get_exact(n, v);
  }
  void num(std::string_view n, double& x) { x = r.get_double(n); }
  template <class T>
  void integer(std::string_view n, T& x) {
    x = static_cast<T>(r.get_int(n));
  }
  void flag(std::string_view n, bool& b) { b = r.get_bool(n); }
  template <class T>
  void pod(std::string_view n, T& x) {
    r.get_pod(n, x);
  }
};

}  // namespace core
}  // namespace crashlink
