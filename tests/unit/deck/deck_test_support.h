#pragma once
// Writes small decks into a fresh temporary folder for the deck tests, and catches messages.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/deck/model_from_deck.h"

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

/// Two unit cubes (mm), part 1 at z in [0, 1], part 2 at z in [1.5, 2.5] above it, mm-t-s.
inline std::vector<std::string> two_cubes() {
  std::vector<std::string> d = {"*KEYWORD", "*NODE"};
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const int id = 1 + c * 8 + k * 4 + j * 2 + i;
          char line[80];
          std::snprintf(line, sizeof line, "%8d%16.4f%16.4f%16.4f", id, static_cast<double>(i),
                        static_cast<double>(j), 1.5 * c + k);
          d.emplace_back(line);
        }
  d.insert(
      d.end(),
      {"*ELEMENT_SOLID",
       "       1       1       1       2       4       3       5       6       8       7",
       "       2       2       9      10      12      11      13      14      16      15", "*PART",
       "lower", "         1         1         1", "*PART", "upper",
       "         2         1         1", "*SECTION_SOLID", "         1         1", "*MAT_ELASTIC",
       "         1   7.85e-9  210000.0       0.3", "*CONTROL_TERMINATION", "    1.0e-5"});
  return d;
}

/// two_cubes() and `more` lines after them.
inline std::vector<std::string> two_cubes_with(const std::vector<std::string>& more) {
  auto d = two_cubes();
  d.insert(d.end(), more.begin(), more.end());
  return d;
}

/// Reads `lines` (+ "*END") as c.k in mm-t-s into `out` (if given); the InputError message with
/// the folder left out, or "".
inline std::string read_lines(const DeckFolder& dir, std::vector<std::string> lines,
                              deck::DeckRead* out = nullptr) {
  lines.push_back("*END");
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  const std::string path = dir.write("c.k", text);
  std::string msg = input_error([&] {
    deck::DeckRead r = deck::read_deck(path, {"mm-t-s", {}});
    if (out) *out = std::move(r);
  });
  for (auto at = msg.find(dir.path("")); at != std::string::npos; at = msg.find(dir.path("")))
    msg.erase(at, dir.path("").size());
  return msg;
}

/// A fixture whose decks are lists of lines read as c.k (read_lines).
class DeckLinesTest : public ::testing::Test {
 protected:
  std::string read(std::vector<std::string> lines, deck::DeckRead* out = nullptr) {
    return read_lines(dir_, std::move(lines), out);
  }
  DeckFolder dir_;
};

}  // namespace crashlink::testing
