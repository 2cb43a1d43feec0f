#pragma once
// Writes small decks into a fresh temporary folder for the deck tests, and catches messages.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/core/errors.h"

namespace crashlink::testing {

/// A temporary folder removed at the end of the test.
class DeckFolder {
 public:
  DeckFolder() {
    dir_ = std::filesystem::temp_directory_path() /
           ("crashlink_deck_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~DeckFolder() { std::filesystem::remove_all(dir_); }
  /// Writes `text` to `name` in the folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const auto p = dir_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

/// The message of the InputError `f` throws ("" if it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace crashlink::testing
