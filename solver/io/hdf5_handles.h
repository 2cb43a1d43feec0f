#pragma once
// RAII ownership of HDF5 identifiers (hid_t) and the few checked HDF5 operations the result
// writer needs. Every failure throws ResultFileError naming the file, the object path and the
// HDF5 call that failed, with the innermost message of HDF5's error stack; HDF5's own automatic
// printing of its error stack is switched off (quiet_hdf5_errors) so nothing else reaches stderr.
//
// Array layouts: 2-D datasets are row-major, [rows, cols]; a row of a [k,3] dataset is one xyz
// triple, so an interleaved xyz array [3n] is written as-is as an [n,3] dataset.
//
// HDF5 is a private dependency of crashlink::io; on Debian's serial package hdf5.h lives under
// /usr/include/hdf5/serial, which targets that only link crashlink::io (tests) do not have on their
// include path: hence the fallback below.
#if __has_include(<hdf5.h>)
#include <hdf5.h>
#else
#include <hdf5/serial/hdf5.h>
#endif

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace crashlink::io {

/// An HDF5 call failed, or the result writer was used wrongly. Message:
/// "<file>:<object path>: <what failed> (HDF5: <innermost HDF5 message>)".
class ResultFileError : public IoError {
 public:
  ResultFileError(const std::string& file, const std::string& object, const std::string& what);
  const std::string& file() const { return file_; }
  const std::string& object() const { return object_; }

 private:
  std::string file_;
  std::string object_;
};

/// Switches off HDF5's automatic error-stack printing for the whole process (idempotent).
/// Failures are reported through ResultFileError instead.
void quiet_hdf5_errors();

/// The innermost entry of the current thread's HDF5 error stack as "function: description", then
/// clears the stack; "" if empty.
std::string hdf5_error_message();

/// Owns one hid_t; Close is the matching H5?close. Move-only. The destructor closes and ignores
/// failures (never throws); close() reports them.
template <herr_t (*Close)(hid_t)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
    }
    return *this;
  }
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  explicit operator bool() const { return valid(); }

  /// Closes now; returns false if HDF5 reported a failure (the handle is released either way).
  bool close() {
    if (id_ < 0) return true;
    const herr_t status = Close(std::exchange(id_, -1));
    return status >= 0;
  }
  void reset() noexcept {
    if (id_ >= 0) {
      Close(std::exchange(id_, -1));
      H5Eclear2(H5E_DEFAULT);  // a failed close in a destructor leaves no stale error entries
    }
  }

 private:
  hid_t id_ = -1;
};

using FileHandle = Handle<H5Fclose>;
using GroupHandle = Handle<H5Gclose>;
using DatasetHandle = Handle<H5Dclose>;
using DataspaceHandle = Handle<H5Sclose>;
using AttributeHandle = Handle<H5Aclose>;
using DatatypeHandle = Handle<H5Tclose>;
using PropertyListHandle = Handle<H5Pclose>;

/// Where an object lives, for error messages and the checked operations below.
struct Location {
  hid_t id;          ///< file, group or dataset the operation acts on
  std::string file;  ///< file path (messages)
  std::string path;  ///< object path inside the file (messages), "/" for the root
  std::string child(const std::string& name) const {
    return path == "/" ? "/" + name : path + "/" + name;
  }
};

/// Creates the file (truncating); throws with the path on failure.
FileHandle create_file(const std::string& path);
/// Opens an existing file read-only.
FileHandle open_file_read(const std::string& path);
GroupHandle create_group(const Location& at, const std::string& name);
GroupHandle open_group(const Location& at, const std::string& name);
bool link_exists(const Location& at, const std::string& name);

/// Writes a whole 1-D or 2-D dataset, dims = {rows} or {rows, cols}; data has rows*cols values.
void write_dataset(const Location& at, const std::string& name, std::span<const double> data,
                   std::span<const hsize_t> dims, const char* units);
void write_dataset(const Location& at, const std::string& name, std::span<const std::int64_t> data,
                   std::span<const hsize_t> dims);
void write_dataset(const Location& at, const std::string& name, std::span<const std::int32_t> data,
                   std::span<const hsize_t> dims);
void write_strings(const Location& at, const std::string& name,
                   const std::vector<std::string>& values);

/// An extendible, chunked double dataset of shape [0, cols] (cols = 0: 1-D [0]) with "units".
DatasetHandle create_extendible(const Location& at, const std::string& name, hsize_t cols,
                                hsize_t chunk_rows, const char* units);
/// Appends rows (rows*cols values, row-major) at the end of an extendible dataset.
void append_rows(const Location& ds, std::span<const double> data, hsize_t cols);

/// A whole double dataset `name` under `at`: rank 1 ([k], cols = 0) or rank 2 ([k, cols]).
/// Returns the values row-major; *rows receives k. Throws ResultFileError (missing, other shape).
std::vector<double> read_doubles(const Location& at, const std::string& name, hsize_t cols,
                                 std::size_t* rows);

/// Attributes (replaced if present).
void write_attribute(const Location& at, const std::string& name, const std::string& value);
void write_attribute(const Location& at, const std::string& name, double value);
void write_attribute(const Location& at, const std::string& name, std::int64_t value);

}  // namespace crashlink::io
