#include "solver/io/hdf5_handles.h"

#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <functional>
#include <numeric>

namespace crashlink::io {

namespace {

// HDF5's H5S_ALL, H5S_UNLIMITED and H5T_VARIABLE expand to C-style casts; -Wold-style-cast is
// silenced for these three definitions only and the rest of the file uses the constants.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
constexpr hid_t kAll = H5S_ALL;
constexpr hsize_t kUnlimited = H5S_UNLIMITED;
constexpr std::size_t kVariableLength = H5T_VARIABLE;
#pragma GCC diagnostic pop

[[noreturn]] void fail(const std::string& file, const std::string& object,
                       const std::string& what) {
  throw ResultFileError(file, object, what);
}

hid_t checked(hid_t id, const Location& at, const std::string& object, const char* what) {
  if (id < 0) fail(at.file, object, what);
  return id;
}

void checked(herr_t status, const std::string& file, const std::string& object, const char* what) {
  if (status < 0) fail(file, object, what);
}

hsize_t element_count(std::span<const hsize_t> dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

void write_whole(const Location& at, const std::string& name, const void* data, std::size_t count,
                 std::span<const hsize_t> dims, hid_t file_type, hid_t memory_type,
                 const char* units) {
  const std::string object = at.child(name);
  if (dims.empty() || dims.size() > 2 || element_count(dims) != count) {
    fail(at.file, object,
         fmt::format("write_dataset: {} values do not fill the requested shape of rank {} "
                     "(internal error: shape and data disagree)",
                     count, dims.size()));
  }
  DataspaceHandle space(
      checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), at, object,
              "H5Screate_simple"));
  DatasetHandle ds(checked(H5Dcreate2(at.id, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT),
                           at, object, "H5Dcreate2 (create dataset)"));
  if (count > 0) {
    checked(H5Dwrite(ds.get(), memory_type, kAll, kAll, H5P_DEFAULT, data), at.file, object,
            "H5Dwrite");
  }
  if (units != nullptr) write_attribute(Location{ds.get(), at.file, object}, "units", units);
  if (!ds.close()) fail(at.file, object, "H5Dclose");
}

struct ErrorWalk {
  std::string api;        // outermost entry: the API function called
  std::string innermost;  // innermost entry: what really failed
};

herr_t walk_error(unsigned n, const H5E_error2_t* e, void* data) {
  auto* walk = static_cast<ErrorWalk*>(data);
  char minor[256] = {};
  H5Eget_msg(e->min_num, nullptr, minor, sizeof minor);
  if (n == 0) {
    walk->innermost = fmt::format("{}: {}{}{}", e->func_name ? e->func_name : "?",
                                  e->desc ? e->desc : "", minor[0] ? " - " : "", minor);
  }
  walk->api = e->func_name ? e->func_name : "?";
  return 0;
}

}  // namespace

ResultFileError::ResultFileError(const std::string& file, const std::string& object,
                                 const std::string& what)
    : IoError([&] {
        std::string msg = fmt::format("{}:{}: {}", file, object, what);
        const std::string detail = hdf5_error_message();
        // A failed write or open says why in "errno = N, error message = '...'": that is the
        // cause a user can act on (No space left on device, Read-only file system, ...).
        const std::string key = "error message = '";
        const auto at = detail.find(key);
        const auto end = at == std::string::npos ? at : detail.find('\'', at + key.size());
        if (end != std::string::npos) {
          const std::string cause = detail.substr(at + key.size(), end - at - key.size());
          const bool full = cause.find("No space left") != std::string::npos ||
                            cause.find("File too large") != std::string::npos ||
                            cause.find("quota") != std::string::npos;
          msg += ": " + cause +
                 (full ? "; free space on that file system or write elsewhere (--out)"
                       : "; check the path and its permissions, or write elsewhere (--out)");
        } else if (!detail.empty()) {
          msg += " (HDF5: " + detail + ")";
        }
        return msg;
      }()),
      file_(file),
      object_(object) {}

namespace {
// No HDF5 clean-up at exit: after a write failed (disk full), H5Fclose fails and leaves the file
// open, and H5_term_library's second try at exit crashed every process (SIGSEGV in
// H5F__close_cb, HDF5 1.10.8). The writers close every object themselves; a file a failure left
// open is abandoned at exit, with what was flushed before readable. H5dont_atexit must come
// before any other HDF5 call: hence a static initializer of this library.
const bool kNoHdf5AtExit = [] {
  H5dont_atexit();
  return true;
}();
}  // namespace

void quiet_hdf5_errors() {
  (void)kNoHdf5AtExit;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

std::string hdf5_error_message() {
  ErrorWalk walk;
  if (H5Eget_num(H5E_DEFAULT) <= 0) return {};
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walk_error, &walk);
  H5Eclear2(H5E_DEFAULT);
  return walk.innermost;
}

FileHandle create_file(const std::string& path) {
  quiet_hdf5_errors();
  // Default file access (weak close degree): the writer closes its objects before the file, and
  // a reader in the same process may open the file while it is being written.
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) {
    // An empty file left by a create that failed half-way (disk full) is no result. (The HDF5
    // error stack, which fail() reads, is untouched by std::filesystem.)
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0)
      std::filesystem::remove(path, ec);
    fail(path, "/",
         "cannot create the result file (H5Fcreate); check the directory "
         "exists and is writable and that no other program holds the file");
  }
  return FileHandle(id);
}

FileHandle open_file_read(const std::string& path) {
  quiet_hdf5_errors();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) fail(path, "/", "cannot open the file for reading (H5Fopen)");
  return FileHandle(id);
}

GroupHandle create_group(const Location& at, const std::string& name) {
  return GroupHandle(checked(H5Gcreate2(at.id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             at, at.child(name), "H5Gcreate2 (create group)"));
}

GroupHandle open_group(const Location& at, const std::string& name) {
  return GroupHandle(checked(H5Gopen2(at.id, name.c_str(), H5P_DEFAULT), at, at.child(name),
                             "H5Gopen2 (open group)"));
}

bool link_exists(const Location& at, const std::string& name) {
  const htri_t e = H5Lexists(at.id, name.c_str(), H5P_DEFAULT);
  if (e < 0) fail(at.file, at.child(name), "H5Lexists");
  return e > 0;
}

void write_dataset(const Location& at, const std::string& name, std::span<const double> data,
                   std::span<const hsize_t> dims, const char* units) {
  write_whole(at, name, data.data(), data.size(), dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, units);
}

void write_dataset(const Location& at, const std::string& name, std::span<const std::int64_t> data,
                   std::span<const hsize_t> dims) {
  write_whole(at, name, data.data(), data.size(), dims, H5T_STD_I64LE, H5T_NATIVE_INT64, nullptr);
}

void write_dataset(const Location& at, const std::string& name, std::span<const std::int32_t> data,
                   std::span<const hsize_t> dims) {
  write_whole(at, name, data.data(), data.size(), dims, H5T_STD_I32LE, H5T_NATIVE_INT32, nullptr);
}

namespace {
DatatypeHandle utf8_string_type(const Location& at, const std::string& object) {
  DatatypeHandle t(checked(H5Tcopy(H5T_C_S1), at, object, "H5Tcopy (string type)"));
  checked(H5Tset_size(t.get(), kVariableLength), at.file, object, "H5Tset_size");
  checked(H5Tset_cset(t.get(), H5T_CSET_UTF8), at.file, object, "H5Tset_cset");
  return t;
}
}  // namespace

void write_strings(const Location& at, const std::string& name,
                   const std::vector<std::string>& values) {
  const std::string object = at.child(name);
  std::vector<const char*> ptrs;
  ptrs.reserve(values.size());
  for (const auto& v : values) ptrs.push_back(v.c_str());
  const hsize_t dims[1] = {values.size()};
  DatatypeHandle type = utf8_string_type(at, object);
  DataspaceHandle space(
      checked(H5Screate_simple(1, dims, nullptr), at, object, "H5Screate_simple"));
  DatasetHandle ds(checked(H5Dcreate2(at.id, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT),
                           at, object, "H5Dcreate2 (create string dataset)"));
  if (!values.empty()) {
    checked(H5Dwrite(ds.get(), type.get(), kAll, kAll, H5P_DEFAULT, ptrs.data()), at.file, object,
            "H5Dwrite");
  }
  if (!ds.close()) fail(at.file, object, "H5Dclose");
}

DatasetHandle create_extendible(const Location& at, const std::string& name, hsize_t cols,
                                hsize_t chunk_rows, const char* units) {
  const std::string object = at.child(name);
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {0, cols};
  const hsize_t max_dims[2] = {kUnlimited, cols};
  const hsize_t chunk[2] = {chunk_rows, cols};
  DataspaceHandle space(
      checked(H5Screate_simple(rank, dims, max_dims), at, object, "H5Screate_simple (extendible)"));
  PropertyListHandle dcpl(checked(H5Pcreate(H5P_DATASET_CREATE), at, object, "H5Pcreate"));
  // No compression on purpose: an unfiltered chunk is rewritten in place, so a run that dies
  // after a flush leaves the flushed rows intact (a filtered chunk may move on rewrite).
  checked(H5Pset_chunk(dcpl.get(), rank, chunk), at.file, object, "H5Pset_chunk");
  DatasetHandle ds(checked(H5Dcreate2(at.id, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                      dcpl.get(), H5P_DEFAULT),
                           at, object, "H5Dcreate2 (create extendible dataset)"));
  write_attribute(Location{ds.get(), at.file, object}, "units", units);
  return ds;
}

void append_rows(const Location& ds, std::span<const double> data, hsize_t cols) {
  const hsize_t width = cols == 0 ? 1 : cols;
  if (data.empty()) return;
  if (data.size() % width != 0) {
    fail(ds.file, ds.path,
         fmt::format("append_rows: {} values are not whole rows of {} (internal error)",
                     data.size(), width));
  }
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t rows = data.size() / width;
  hsize_t dims[2] = {0, cols};
  {
    DataspaceHandle space(checked(H5Dget_space(ds.id), ds, ds.path, "H5Dget_space"));
    checked(H5Sget_simple_extent_dims(space.get(), dims, nullptr), ds.file, ds.path,
            "H5Sget_simple_extent_dims");
  }
  const hsize_t start[2] = {dims[0], 0};
  const hsize_t count[2] = {rows, cols};
  const hsize_t new_dims[2] = {dims[0] + rows, cols};
  checked(H5Dset_extent(ds.id, new_dims), ds.file, ds.path, "H5Dset_extent (extend history)");
  DataspaceHandle file_space(checked(H5Dget_space(ds.id), ds, ds.path, "H5Dget_space"));
  checked(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
          ds.file, ds.path, "H5Sselect_hyperslab");
  DataspaceHandle memory_space(
      checked(H5Screate_simple(rank, count, nullptr), ds, ds.path, "H5Screate_simple"));
  checked(H5Dwrite(ds.id, H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                   data.data()),
          ds.file, ds.path, "H5Dwrite (append history rows)");
}

namespace {
void write_scalar_attribute(const Location& at, const std::string& name, hid_t file_type,
                            hid_t memory_type, const void* value) {
  const std::string object = at.path + "@" + name;
  const htri_t exists = H5Aexists(at.id, name.c_str());
  if (exists < 0) fail(at.file, object, "H5Aexists");
  if (exists > 0) checked(H5Adelete(at.id, name.c_str()), at.file, object, "H5Adelete");
  DataspaceHandle space(checked(H5Screate(H5S_SCALAR), at, object, "H5Screate"));
  AttributeHandle a(
      checked(H5Acreate2(at.id, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), at,
              object, "H5Acreate2 (create attribute)"));
  checked(H5Awrite(a.get(), memory_type, value), at.file, object, "H5Awrite");
  if (!a.close()) fail(at.file, object, "H5Aclose");
}
}  // namespace

void write_attribute(const Location& at, const std::string& name, const std::string& value) {
  DatatypeHandle type = utf8_string_type(at, at.path + "@" + name);
  const char* ptr = value.c_str();
  write_scalar_attribute(at, name, type.get(), type.get(), &ptr);
}

void write_attribute(const Location& at, const std::string& name, double value) {
  write_scalar_attribute(at, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(const Location& at, const std::string& name, std::int64_t value) {
  write_scalar_attribute(at, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

std::vector<double> read_doubles(const Location& at, const std::string& name, hsize_t cols,
                                 std::size_t* rows) {
  const std::string object = at.child(name);
  if (!link_exists(at, name)) {
    throw ResultFileError(at.file, object,
                          "dataset missing (the file does not follow docs/result-format.md)");
  }
  DatasetHandle ds(H5Dopen2(at.id, name.c_str(), H5P_DEFAULT));
  if (!ds) throw ResultFileError(at.file, object, "H5Dopen2 (open dataset)");
  DataspaceHandle space(H5Dget_space(ds.get()));
  if (!space) throw ResultFileError(at.file, object, "H5Dget_space");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  const int want_rank = cols == 0 ? 1 : 2;
  std::array<hsize_t, 2> dims{0, 0};
  if (rank != want_rank || H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0 ||
      (cols != 0 && dims[1] != cols)) {
    throw ResultFileError(
        at.file, object,
        fmt::format("shape is rank {} [{}, {}]; expected {} (docs/result-format.md)", rank, dims[0],
                    dims[1], cols == 0 ? "[k]" : fmt::format("[k, {}]", cols)));
  }
  std::vector<double> out(dims[0] * (cols == 0 ? 1 : cols));
  if (!out.empty() &&
      H5Dread(ds.get(), H5T_NATIVE_DOUBLE, kAll, kAll, H5P_DEFAULT, out.data()) < 0) {
    throw ResultFileError(at.file, object, "H5Dread");
  }
  *rows = static_cast<std::size_t>(dims[0]);
  return out;
}

}  // namespace crashlink::io
