#pragma once
// Shared by the CURVE suites: key files in a fresh temp directory (removed at the end), made
// with the real `crashlink keygen` code (transport/curve_keygen.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "transport/curve_keygen.h"

namespace crashlink::transport::test {

/// A temp directory of key files for one test.
class KeyDir {
 public:
  KeyDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "-" + info->name();
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    dir_ = std::filesystem::temp_directory_path() /
           ("crashlink-curve-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~KeyDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  KeyDir(const KeyDir&) = delete;
  KeyDir& operator=(const KeyDir&) = delete;

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// `crashlink keygen --out DIR/name`.
  CurveKeyFiles pair(const std::string& name) const {
    return write_curve_keypair(path(name), false);
  }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace crashlink::transport::test
