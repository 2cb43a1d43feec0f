#pragma once
// For the reader's error tests: the line a mistake sits on, found by its text, so that each test
// states the mistake once.
#include <gtest/gtest.h>

#include <string>

namespace crashlink::io::testing {

/// 1-based line of the first occurrence of `marker` in `text`.
inline int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << "marker '" << marker << "' not in the test text";
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

}  // namespace crashlink::io::testing
