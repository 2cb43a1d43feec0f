#pragma once
// Test helpers: read result.h5 back with the plain HDF5 C API (not through the writer's helpers,
// so a mistake in those cannot hide itself), and a tiny model to write.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/io/hdf5_handles.h"  // hdf5.h (with the Debian include-path fallback) and Handle
#include "solver/model/model.h"

namespace crashlink::io::test {

/// A fresh, empty directory under the system temp dir, unique per test.
inline std::string fresh_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / "crashlink_io_tests" /
      (std::string(info->test_suite_name()) + "." + info->name() + "." + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p.string();
}

/// Two parts sharing no node: one Hex8 (nodes 0-7, unit cube) and two Shell4 on z = 2 (nodes 8-13),
/// one node probe and one rigid-body probe.
inline model::Model small_model() {
  model::Model m;
  m.name = "tiny";
  const double cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                             {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) {
    m.nodes.id.push_back(101 + i);
    for (double c : cube[i]) m.nodes.x0.push_back(c);
  }
  const double plate[6][3] = {{0, 0, 2}, {1, 0, 2}, {2, 0, 2}, {0, 1, 2}, {1, 1, 2}, {2, 1, 2}};
  for (int i = 0; i < 6; ++i) {
    m.nodes.id.push_back(201 + i);
    for (double c : plate[i]) m.nodes.x0.push_back(c);
  }
  model::Part hex;
  hex.name = "block";
  hex.kind = model::ElementKind::Hex8;
  hex.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  hex.element_id = {11};
  model::Part shell;
  shell.name = "plate";
  shell.kind = model::ElementKind::Shell4;
  shell.connectivity = {8, 9, 12, 11, 9, 10, 13, 12};
  shell.element_id = {21, 22};
  shell.thickness_m = 0.001;
  m.parts = {hex, shell};
  model::RigidBody rb;
  rb.name = "impactor";
  m.rigid_bodies.push_back(rb);
  m.probes.push_back(model::Probe{"tip", model::Probe::Kind::Node, 6});
  m.probes.push_back(model::Probe{"head", model::Probe::Kind::RigidBody, 0});
  return m;
}

/// Read-only view of a result file through the HDF5 C API.
class H5Reader {
 public:
  explicit H5Reader(const std::string& path) : file_(open_file_read(path)) {}

  bool exists(const std::string& path) const {
    // H5Lexists on each prefix: an intermediate group that does not exist is not an error.
    std::string prefix;
    std::size_t pos = 1;
    while (pos <= path.size()) {
      const std::size_t next = path.find('/', pos);
      prefix = path.substr(0, next);
      if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      if (next == std::string::npos) break;
      pos = next + 1;
    }
    return true;
  }

  std::vector<hsize_t> dims(const std::string& path) const {
    DatasetHandle ds(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT));
    EXPECT_TRUE(ds.valid()) << path;
    DataspaceHandle sp(H5Dget_space(ds.get()));
    std::vector<hsize_t> d(static_cast<std::size_t>(H5Sget_simple_extent_ndims(sp.get())));
    H5Sget_simple_extent_dims(sp.get(), d.data(), nullptr);
    return d;
  }

  std::vector<double> doubles(const std::string& path) const {
    return read<double>(path, H5T_NATIVE_DOUBLE);
  }
  std::vector<std::int64_t> int64s(const std::string& path) const {
    return read<std::int64_t>(path, H5T_NATIVE_INT64);
  }
  std::vector<std::int32_t> int32s(const std::string& path) const {
    return read<std::int32_t>(path, H5T_NATIVE_INT32);
  }

  std::vector<std::string> strings(const std::string& path) const {
    DatasetHandle ds(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT));
    DatatypeHandle t(H5Dget_type(ds.get()));
    const std::size_t n = static_cast<std::size_t>(dims(path).at(0));
    std::vector<char*> ptrs(n, nullptr);
    EXPECT_GE(H5Dread(ds.get(), t.get(), 0, 0, H5P_DEFAULT, ptrs.data()), 0) << path;
    std::vector<std::string> out(ptrs.begin(), ptrs.end());
    DataspaceHandle sp(H5Dget_space(ds.get()));
    H5Dvlen_reclaim(t.get(), sp.get(), H5P_DEFAULT, ptrs.data());
    return out;
  }

  /// Attribute `name` of the object at `path`.
  double attr_double(const std::string& path, const std::string& name) const {
    double v = 0;
    read_attr(path, name, H5T_NATIVE_DOUBLE, &v);
    return v;
  }
  std::int64_t attr_int64(const std::string& path, const std::string& name) const {
    std::int64_t v = 0;
    read_attr(path, name, H5T_NATIVE_INT64, &v);
    return v;
  }
  std::string attr_string(const std::string& path, const std::string& name) const {
    AttributeHandle a(
        H5Aopen_by_name(file_.get(), path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
    if (!a) {
      ADD_FAILURE() << "no attribute " << path << "@" << name;
      return {};
    }
    DatatypeHandle t(H5Aget_type(a.get()));
    char* s = nullptr;
    EXPECT_GE(H5Aread(a.get(), t.get(), &s), 0);
    std::string out = s != nullptr ? s : "";
    H5free_memory(s);
    return out;
  }

 private:
  template <class T>
  std::vector<T> read(const std::string& path, hid_t type) const {
    DatasetHandle ds(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT));
    if (!ds) {
      ADD_FAILURE() << "no dataset " << path;
      return {};
    }
    std::size_t n = 1;
    for (hsize_t d : dims(path)) n *= static_cast<std::size_t>(d);
    std::vector<T> v(n);
    if (n > 0) {
      EXPECT_GE(H5Dread(ds.get(), type, 0, 0, H5P_DEFAULT, v.data()), 0) << path;  // 0: H5S_ALL
    }
    return v;
  }
  void read_attr(const std::string& path, const std::string& name, hid_t type, void* v) const {
    AttributeHandle a(
        H5Aopen_by_name(file_.get(), path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
    if (!a) {
      ADD_FAILURE() << "no attribute " << path << "@" << name;
      return;
    }
    EXPECT_GE(H5Aread(a.get(), type, v), 0) << path << "@" << name;
  }

  FileHandle file_;
};

}  // namespace crashlink::io::test
